//! Statistics for comparing strategies (being written).
