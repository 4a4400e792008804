//! k-means clustering (Lloyd with k-means++ seeding, seeded), for RFE, MTSP and SGA.
//!
//! (Being written.)
