//! sense (being written)
