//! Map files in and out (being written).
