//! The wobble pipeline and tools.
