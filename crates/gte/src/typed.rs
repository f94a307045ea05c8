//! Typed fixed-point API over the register-level engine.
