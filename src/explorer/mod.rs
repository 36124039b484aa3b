//! The interactive explorer (in progress).
