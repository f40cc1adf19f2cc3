//! `evaluate --shard I/N` and `evaluate merge`: the tournament's shard files (the library's
//! [`thermonav::evaluation::shard`] with the fingerprint of the inputs and settings and the
//! `--imu-rotation` text), and their merge into the files one unsharded run writes.

use crate::args::EvaluateMergeArgs;
use crate::failure::{Classify, Failure};
use crate::navigation::tournament_files::{EchoText, EvaluationFile, write_outcome};
use crate::settings::navigation::{EvaluateSettings, FilterRun, NoiseSource};
use crate::settings::paths::Io;
use anyhow::anyhow;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::io::Read;
use std::path::{Path, PathBuf};
use thermonav::evaluation::experiment::{Replicates, Tournament};
use thermonav::evaluation::scenario::Scenario;
use thermonav::evaluation::shard::{Shard, TournamentShard, merge_shards};
use thermonav::nav::run_options::RunOptions;
use thermonav_io::write_json_atomically;

/// What a shard file holds.
#[derive(Debug, Serialize, Deserialize)]
struct ShardFile {
    /// The runs, the frame and the fingerprint.
    tournament: TournamentShard,
    /// The `--imu-rotation` the IMU record was turned by, when given (for evaluation.json).
    imu_rotation: Option<String>,
    /// The run options of every candidate's run (for evaluation.json).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    run_options: Option<RunOptions>,
}

/// What `evaluate --shard` reports.
#[derive(Debug, Serialize)]
pub struct ShardWritten {
    /// The shard's index, 1-based.
    pub shard_index: usize,
    /// Shards in all.
    pub shard_count: usize,
    /// Runs in this shard.
    pub runs: usize,
    /// Runs in all the shards.
    pub total_runs: usize,
    /// The shard file.
    pub shard_file: PathBuf,
}

/// The name of shard `shard`'s file in its --out folder.
pub fn shard_file_name(shard: Shard) -> String {
    format!("shard-{}-of-{}.json", shard.index, shard.count)
}

/// Runs `shard`'s share of the tournament and writes it as `out/shard-I-of-N.json`.
pub fn run_and_write_shard(
    (tournament, main, replicates): (&Tournament, &Scenario, &Replicates),
    shard: Shard,
    (s, run): (&EvaluateSettings, &FilterRun),
) -> Result<ShardWritten, Failure> {
    let fingerprint = fingerprint(s, run)?;
    let bar = crate::progress::bar(
        tournament.runs(replicates).div_ceil(shard.count),
        "shard runs",
    );
    let mut sharded = tournament
        .run_shard(main, replicates, shard, &|| bar.inc(1))
        .map_err(|e| anyhow!("{e}"))
        .data()?;
    bar.finish_and_clear();
    sharded.fingerprint = fingerprint;
    let written = ShardWritten {
        shard_index: shard.index,
        shard_count: shard.count,
        runs: sharded.runs.len(),
        total_runs: sharded.frame.runs(),
        shard_file: s.out.join(shard_file_name(shard)),
    };
    let file = ShardFile {
        tournament: sharded,
        imu_rotation: crate::settings::imu::rotation_text(&run.files.imu_options),
        run_options: Some(s.options.clone()),
    };
    crate::campaign::create_folder(&s.out)?;
    write_json_atomically(&written.shard_file, &file).data()?;
    Ok(written)
}

/// The hashes (FNV-1a, 64 bits, hex) of every input file's bytes and of the settings that
/// decide the runs, by name: shards whose entries differ are not one tournament.
fn fingerprint(s: &EvaluateSettings, run: &FilterRun) -> Result<BTreeMap<String, String>, Failure> {
    let (noise_name, noise) = match &run.noise {
        NoiseSource::Bank(p) => ("--bank", p),
        NoiseSource::Profile(p) => ("--profile", p),
    };
    let files = [
        ("--imu", Some(&run.files.imu)),
        ("--gnss", Some(&run.files.gnss)),
        ("--reference", Some(&run.files.reference)),
        (noise_name, Some(noise)),
        ("--thermal-from", run.thermal_from.as_ref()),
        ("--initial-from", run.initial_from.as_ref()),
        ("--truth", s.truth.as_ref()),
        ("--datasheet", s.datasheet.as_ref()),
    ];
    let mut entries = BTreeMap::new();
    for (name, path) in files {
        if let Some(path) = path {
            entries.insert(format!("{name} (file contents)"), hex(file_fnv1a_64(path)?));
        }
    }
    let settings = settings_text(s, run);
    entries.insert(
        "settings".into(),
        hex(fnv1a_64(FNV_OFFSET, settings.as_bytes())),
    );
    Ok(entries)
}

/// The settings that decide the runs, as text (paths and the shard left out: they may differ
/// between the jobs of one tournament).
fn settings_text(s: &EvaluateSettings, run: &FilterRun) -> String {
    format!(
        "{:?} {:?} {:?} {:?} {:?} {:?} {} {} {:?}",
        s.scheduling,
        s.compensation,
        s.options,
        s.temperature,
        s.filters,
        s.outages,
        s.extra_replicates,
        s.seed,
        run.files.imu_options,
    )
}

fn hex(hash: u64) -> String {
    format!("{hash:016x}")
}

/// FNV-1a's 64-bit offset basis.
const FNV_OFFSET: u64 = 0xcbf2_9ce4_8422_2325;
/// FNV-1a's 64-bit prime.
const FNV_PRIME: u64 = 0x0000_0100_0000_01b3;

/// FNV-1a (64 bits) of `bytes`, continued from `hash` (start from [`FNV_OFFSET`]).
fn fnv1a_64(hash: u64, bytes: &[u8]) -> u64 {
    bytes
        .iter()
        .fold(hash, |h, b| (h ^ u64::from(*b)).wrapping_mul(FNV_PRIME))
}

/// FNV-1a (64 bits) of a file's bytes, read in pieces.
fn file_fnv1a_64(path: &Path) -> Result<u64, Failure> {
    let failed = |e: std::io::Error| anyhow!("{}: cannot read: {e}", path.display());
    let mut file = std::fs::File::open(path).map_err(failed).data()?;
    let mut buffer = vec![0u8; 1 << 20];
    let mut hash = FNV_OFFSET;
    loop {
        let n = file.read(&mut buffer).map_err(failed).data()?;
        if n == 0 {
            return Ok(hash);
        }
        hash = fnv1a_64(hash, &buffer[..n]);
    }
}

/// `evaluate merge`: the shard files read, checked to be one complete tournament, merged and
/// written as one unsharded run writes `out`.
pub fn merge(args: &EvaluateMergeArgs) -> Result<EvaluationFile, Failure> {
    let files = shard_files(&args.shards)?;
    Io::new()
        .inputs("shard", &files)
        .output("report", &args.out.join("evaluation.json"))
        .output_folder("per-model error folder", &args.out.join("errors"))
        .check()?;
    let read: Vec<(String, ShardFile)> = files.iter().map(read_shard).collect::<Result<_, _>>()?;
    // The fingerprint (checked by the merge) makes the shards' rotation and options one.
    // A sharded run estimates no time offset (refused with --shard).
    let echo = match read.first() {
        Some((_, f)) => EchoText {
            imu_rotation: f.imu_rotation.clone(),
            run_options: f.run_options.clone(),
            time_offset: None,
        },
        None => EchoText::default(),
    };
    let shards: Vec<(String, TournamentShard)> =
        read.into_iter().map(|(n, f)| (n, f.tournament)).collect();
    let merged = merge_shards(&shards).map_err(|e| anyhow!("{e}")).data()?;
    write_outcome((merged.report, &merged.main), &[], (&args.out, echo))
}

/// The shard files of each argument: a file itself, or a folder's `shard-*-of-*.json` in
/// name order (a folder without one is refused).
fn shard_files(arguments: &[PathBuf]) -> Result<Vec<PathBuf>, Failure> {
    let mut files = Vec::new();
    for path in arguments {
        if !path.is_dir() {
            files.push(path.clone());
            continue;
        }
        let failed = |e: std::io::Error| anyhow!("{}: cannot list: {e}", path.display());
        let mut found: Vec<PathBuf> = (std::fs::read_dir(path).map_err(failed).data()?)
            .filter_map(|entry| entry.ok().map(|e| e.path()))
            .filter(|p| is_shard_file_name(p))
            .collect();
        if found.is_empty() {
            return Err(anyhow!(
                "{}: no shard-I-of-N.json file in this folder",
                path.display()
            ))
            .data();
        }
        found.sort();
        files.extend(found);
    }
    Ok(files)
}

fn is_shard_file_name(path: &Path) -> bool {
    let name = path.file_name().and_then(|n| n.to_str()).unwrap_or("");
    name.starts_with("shard-") && name.ends_with(".json") && name.contains("-of-")
}

/// One shard file, errors naming it (serde_json's message gives the line and column).
fn read_shard(path: &PathBuf) -> Result<(String, ShardFile), Failure> {
    let name = path.display().to_string();
    let text = std::fs::read_to_string(path)
        .map_err(|e| anyhow!("{name}: cannot read: {e}"))
        .data()?;
    let file: ShardFile = serde_json::from_str(&text)
        .map_err(|e| anyhow!("{name}: not a shard file of `evaluate --shard` ({e})"))
        .data()?;
    Ok((name, file))
}

#[cfg(test)]
mod tests {
    use super::*;

    // Oracle: the FNV-1a 64-bit test vectors published with the algorithm (Fowler, Noll, Vo;
    // draft-eastlake-fnv, appendix C): "" and "a" and "foobar".
    #[test]
    fn fnv1a_64_matches_the_published_test_vectors() {
        assert_eq!(fnv1a_64(FNV_OFFSET, b""), 0xcbf29ce484222325);
        assert_eq!(fnv1a_64(FNV_OFFSET, b"a"), 0xaf63dc4c8601ec8c);
        assert_eq!(fnv1a_64(FNV_OFFSET, b"foobar"), 0x85944171f73967e8);
        // In pieces as in one.
        assert_eq!(
            fnv1a_64(fnv1a_64(FNV_OFFSET, b"foo"), b"bar"),
            0x85944171f73967e8
        );
    }
}
