//! world (being written)
