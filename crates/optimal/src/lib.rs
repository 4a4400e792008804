//! `optimal`: offline optimal exploration paths (being written).
