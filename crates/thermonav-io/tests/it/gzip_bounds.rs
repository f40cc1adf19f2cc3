//! Issue 37 row 3: a gzip log that expands far beyond what any log compresses is refused
//! after reading a bounded amount, naming the file, instead of exhausting memory.

use flate2::Compression;
use flate2::write::GzEncoder;
use std::io::Write;
use thermonav_io::{DOCUMENT_LIMIT_BYTES, MAX_GZIP_EXPANSION};

/// A gzip file of `zeros` zero bytes at `path`; returns its stored size.
fn gzip_of_zeros(path: &std::path::Path, zeros: usize) -> u64 {
    let mut encoder = GzEncoder::new(std::fs::File::create(path).unwrap(), Compression::fast());
    let block = vec![0_u8; 1 << 20];
    for _ in 0..zeros >> 20 {
        encoder.write_all(&block).unwrap();
    }
    encoder.finish().unwrap();
    std::fs::metadata(path).unwrap().len()
}

#[test]
fn a_gzip_bomb_is_refused_at_its_bound_for_every_whole_file_reader() {
    let dir = tempfile::tempdir().unwrap();
    let bomb = dir.path().join("bomb.ulg.gz");
    // 256 MiB of zeros compress about a thousand times: far beyond the bound.
    let stored = gzip_of_zeros(&bomb, 256 << 20);
    let limit = DOCUMENT_LIMIT_BYTES + MAX_GZIP_EXPANSION * stored;
    assert!(
        limit < 256 << 20,
        "the fixture must exceed the bound ({limit} bytes)"
    );
    let ulog = thermonav_io::ulog::read_ulog_file(&bomb)
        .unwrap_err()
        .to_string();
    assert!(
        ulog.contains("bomb.ulg.gz") && ulog.contains("decompression bomb"),
        "{ulog}"
    );
    let bin = dir.path().join("bomb.bin.gz");
    std::fs::copy(&bomb, &bin).unwrap();
    let dataflash = thermonav_io::dataflash::read_dataflash_file(&bin)
        .unwrap_err()
        .to_string();
    assert!(
        dataflash.contains("bomb.bin.gz") && dataflash.contains("decompression bomb"),
        "{dataflash}"
    );
    let mcap = dir.path().join("bomb.mcap.gz");
    std::fs::copy(&bomb, &mcap).unwrap();
    let bag = thermonav_io::ros::read_bag_file(&mcap, None)
        .unwrap_err()
        .to_string();
    assert!(
        bag.contains("bomb.mcap.gz") && bag.contains("decompression bomb"),
        "{bag}"
    );
}

#[test]
fn a_gzip_within_the_bound_reads_whole() {
    // 8 MiB of zeros stay within the 64 MiB floor: read through, then refused for what they
    // are (not a ULog), not as a bomb.
    let dir = tempfile::tempdir().unwrap();
    let small = dir.path().join("small.ulg.gz");
    gzip_of_zeros(&small, 8 << 20);
    let error = thermonav_io::ulog::read_ulog_file(&small)
        .unwrap_err()
        .to_string();
    assert!(!error.contains("decompression bomb"), "{error}");
}
