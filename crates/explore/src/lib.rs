//! explore (being written)
