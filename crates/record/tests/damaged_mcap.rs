//! A recording whose bytes changed after it was written is refused as damaged, by the
//! checksums MCAP keeps, rather than read as another map.

mod common;

/// A recording of the map messages `maps` on `/map` in one uncompressed chunk.
fn uncompressed(maps: &[Vec<u8>]) -> Vec<u8> {
    common::recording_with(None, &[], maps)
}

/// Regression: chunk checksums were not checked, so a cell changed inside a recording was
/// read as a wall without a word (and other changes as misleading errors).
#[test]
fn regression_a_changed_cell_is_refused_as_damage() {
    let cells: Vec<i8> = vec![0, 0, 100, -1, 0, 100, 0, 0, -1, -1, 0, 0];
    let bytes = uncompressed(&[common::grid_message(4, 3, cells.clone())]);
    let (map, _) = record::last_map(&bytes, None).expect("the recording as written");
    assert_eq!(map.cells.len(), 12);
    let at = bytes
        .windows(cells.len())
        .position(|w| w.iter().zip(&cells).all(|(&b, &c)| b == c as u8))
        .expect("the cells, uncompressed");
    let mut changed = bytes.clone();
    changed[at] = 100; // a free cell made a wall
    let e = record::last_map(&changed, None)
        .expect_err("a changed chunk")
        .to_string();
    assert!(e.contains("damaged: Chunk CRC failed"), "{e}");
}

/// Regression: an empty file and one cut short both said "MCAP file ended in the middle of
/// a record".
#[test]
fn regression_empty_and_cut_short_recordings_say_so() {
    let e = record::last_map(&[], None).expect_err("empty").to_string();
    assert_eq!(e, "expected an MCAP file, found: an empty file");
    let bytes = uncompressed(&[common::grid_message(2, 1, vec![0, 100])]);
    let e = record::last_map(&bytes[..bytes.len() / 2], None)
        .expect_err("cut short")
        .to_string();
    assert!(
        e.ends_with("ends in the middle of a record: cut short, or still being written"),
        "{e}"
    );
}

/// Regression: `--topic map` did not find `/map`, the ROS 2 name of the same topic.
#[test]
fn regression_a_topic_is_found_without_its_leading_slash() {
    let bytes = uncompressed(&[common::grid_message(2, 1, vec![0, 100])]);
    let (map, topic) = record::last_map(&bytes, Some("map")).expect("map is /map");
    assert_eq!((map.width(), topic.as_str()), (2, "/map"));
    let e = record::last_map(&bytes, Some("scan"))
        .expect_err("no such topic")
        .to_string();
    assert!(e.contains("messages on topic scan"), "{e}");
}

/// Regression: a changed byte inside a compressed chunk was "expected an MCAP file, found:
/// I/O error from writing, or reading a compression stream" (lz4), or a decompression
/// error, since a chunk's checksum is of its decompressed bytes and decompressing fails
/// first. Every such change is now refused as damage, with what the decompressor said.
#[test]
fn regression_a_changed_compressed_chunk_is_refused_as_damage() {
    let cells: Vec<i8> = (0..400)
        .map(|i| match i {
            _ if i % 7 == 0 => 100,
            _ if i % 5 == 0 => -1,
            _ => 0,
        })
        .collect();
    for compression in [mcap::Compression::Lz4, mcap::Compression::Zstd] {
        let maps = [common::grid_message(20, 20, cells.clone())];
        let bytes = common::recording_with(Some(compression), &[], &maps);
        record::last_map(&bytes, None).expect("the recording as written");
        let mut undecompressed = 0;
        for at in 0..bytes.len() {
            let mut changed = bytes.clone();
            changed[at] ^= 0x5a;
            let Err(e) = record::last_map(&changed, None) else {
                continue;
            };
            let e = e.to_string();
            assert!(
                !e.contains("compression stream")
                    && !e.contains("found: Error during decompression"),
                "{compression:?}, byte {at}: {e}"
            );
            if e.starts_with("damaged: a compressed chunk does not decompress (") {
                undecompressed += 1;
            }
        }
        assert!(
            undecompressed > 0,
            "{compression:?}: no change failed to decompress"
        );
    }
}
