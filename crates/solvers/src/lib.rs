//! Linear and nonlinear solver backends for capstan. Knows no physics.
