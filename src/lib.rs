//! capstan
