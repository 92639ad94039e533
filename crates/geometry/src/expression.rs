//! Math expressions in one variable `t`.
