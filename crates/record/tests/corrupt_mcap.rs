//! Corrupt recordings are refused with an error, not read into huge allocations.

/// Regression (found by the `mcap` fuzz target): a record inside a compressed chunk whose
/// length field reads 0x6e6f72662f000009 bytes made `mcap::MessageStream` try to allocate
/// that much and abort the process. The reader now bounds every record's length first.
#[test]
fn a_corrupt_chunk_record_length_is_refused_not_allocated() {
    let bytes = include_bytes!("data/corrupt-chunk-length.mcap");
    let e = record::last_map(bytes, None).unwrap_err().to_string();
    assert!(e.starts_with("expected an MCAP file, found: "), "{e}");
    assert!(e.contains("length exceeds limit"), "{e}");
    assert!(record::last_map(bytes, Some("/map")).is_err());
}
