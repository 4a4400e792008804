//! Open travelling-salesman routes by path distance (nearest neighbour, 2-opt, Or-opt), for MTSP.
//!
//! (Being written.)
