//! Friction laws and membrane capstan models.
