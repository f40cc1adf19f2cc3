//! Rows of the reliability issue: an output never overwrites an input, a request never asks
//! for more than the data can use, a closed stdout ends a command quietly, and values outside
//! physics are refused.

use super::{arg, files_in, imu_csv, outcome, thermonav, write_file};
use std::path::Path;
use std::process::{Command, Stdio};

/// Runs `words` with `@NAME` replaced by `dir/NAME`.
fn run_in(dir: &Path, words: &str) -> (i32, String, String) {
    let args: Vec<String> = words
        .split_whitespace()
        .map(|w| match w.strip_prefix('@') {
            Some(name) => arg(&dir.join(name)).to_string(),
            None => w.to_string(),
        })
        .collect();
    let refs: Vec<&str> = args.iter().map(String::as_str).collect();
    outcome(&thermonav(&refs))
}

/// A static record at 100 Hz with the given temperature column.
fn static_record(rows: usize, temp_c: f64) -> String {
    let plain = imu_csv(rows, 100.0, |c, t| match c {
        5 => -9.80665 + 1e-3 * (t * 3.0).sin(),
        _ => 1e-3 * (t * (c as f64 + 5.0)).sin(),
    });
    let mut lines = plain.lines();
    let mut text = format!("{},temp_c\n", lines.next().unwrap_or_default());
    for line in lines {
        text.push_str(&format!("{line},{temp_c}\n"));
    }
    text
}

// Each command names one of its inputs as an output (directly, or as the sidecar it writes
// beside the output); it must refuse with exit 2 before reading or writing anything, leaving
// the folder exactly as it was.
#[test]
fn an_output_that_is_an_input_is_refused_before_anything_is_read() {
    let cases = [
        "filter @a.csv --cutoff-hz 5 --out @a.csv",
        "filter @a.csv --cutoff-hz 5 --out @./a.csv",
        "integrate --imu @a.csv --gnss @g.csv --bank @b.json --out @a.csv",
        "integrate --imu @a.csv --gnss @sol.states.csv --bank @b.json --out @sol.csv",
        "integrate --imu @a.csv --gnss @g.csv --bank @sol.innovations.csv --out @sol.csv",
        "characterize @a.csv --temperature-c 20 --out @a.csv",
        "convert @g.pos --out @g.pos",
        "evaluate --imu @errors/a.csv --gnss @g.csv --reference @r.csv --bank @b.json --out @.",
        "evaluate --imu @a.csv --gnss @g.csv --reference @evaluation.json --bank @b.json --out @.",
    ];
    for case in cases {
        let dir = tempfile::tempdir().unwrap();
        std::fs::create_dir(dir.path().join("errors")).unwrap();
        let names = [
            "a.csv",
            "g.csv",
            "b.json",
            "r.csv",
            "g.pos",
            "sol.states.csv",
            "sol.innovations.csv",
            "evaluation.json",
            "errors/a.csv",
        ];
        for name in names {
            write_file(dir.path(), name, "an input\n");
        }
        let before = files_in(dir.path());
        let (code, _, stderr) = run_in(dir.path(), case);
        assert_eq!(code, 2, "{case}: {stderr}");
        assert!(
            stderr.contains("would overwrite the input"),
            "{case}: {stderr}"
        );
        assert_eq!(files_in(dir.path()), before, "{case}");
        for name in names {
            let text = std::fs::read_to_string(dir.path().join(name)).unwrap();
            assert_eq!(text, "an input\n", "{case}: {name} changed");
        }
    }
}

// A hard link is the same file under another name.
#[test]
fn a_hard_link_to_an_input_is_refused_as_an_output() {
    let dir = tempfile::tempdir().unwrap();
    let input = write_file(dir.path(), "a.csv", &static_record(200, 20.0));
    std::fs::hard_link(&input, dir.path().join("same.csv")).unwrap();
    let (code, _, stderr) = run_in(dir.path(), "filter @a.csv --cutoff-hz 5 --out @same.csv");
    assert_eq!(code, 2, "{stderr}");
    assert_eq!(
        std::fs::read_to_string(&input).unwrap(),
        static_record(200, 20.0)
    );
}

// Settings resolve before any file is read: a bad outage specification is named even though
// none of the files exists.
#[test]
fn a_bad_outage_specification_is_refused_before_the_files_are_read() {
    let dir = tempfile::tempdir().unwrap();
    let (code, _, stderr) = run_in(
        dir.path(),
        "integrate --outages bogus --imu /nonexistent --gnss /nonexistent --bank /nonexistent --out @s.csv",
    );
    assert_eq!(code, 2, "{stderr}");
    assert!(
        stderr.contains("outage specification \"bogus\""),
        "{stderr}"
    );
    assert!(!stderr.contains("nonexistent"), "{stderr}");
    assert!(files_in(dir.path()).is_empty());
}

// Requests bounded by the data or a documented limit, refused before anything is allocated:
// 1e12 periodic outages (16 TB as a list) over 20 s of data, a million Monte Carlo
// replicates (each is every model through every filter), the same chamber set point twice.
#[test]
fn requests_beyond_the_data_or_the_documented_limits_are_refused_at_once() {
    let dir = tempfile::tempdir().unwrap();
    write_file(dir.path(), "imu.csv", &static_record(2000, 20.0));
    let gnss: String = (0..=20).map(|k| format!("{k}.0,48.1,11.5,500\n")).collect();
    write_file(
        dir.path(),
        "gnss.csv",
        &format!("t_s,lat_deg,lon_deg,h_m\n{gnss}"),
    );
    let (code, _, stderr) = run_in(dir.path(), "simulate profile --out @p.toml");
    assert_eq!(code, 0, "{stderr}");
    let cases = [
        (
            "integrate --imu @imu.csv --gnss @gnss.csv --profile @p.toml --outages every:10,5,20,1000000000000 --out @s.csv",
            "not inside the data",
        ),
        (
            "integrate --imu @imu.csv --gnss @gnss.csv --profile @p.toml --outages every:1,5,0,1000000000000 --out @s.csv",
            "overlap",
        ),
        (
            "evaluate --imu @imu.csv --gnss @gnss.csv --reference @r.csv --bank @b.json --monte-carlo 1000000 --out @e",
            "at most 1000 replicates",
        ),
        (
            "simulate chamber --temperatures-c=20,20 --duration-s 10 --out @c",
            "twice",
        ),
        (
            "integrate --imu @imu.csv --gnss @gnss.csv --profile @p.toml --output-rate-hz 1e9 --out @s.csv",
            "above 5000 Hz",
        ),
        (
            "fir --fs-hz 100 --cutoff-hz 10 --transition-hz 1e-300",
            "taps (more than 2000000): widen the transition band",
        ),
    ];
    for (case, needle) in cases {
        let (code, _, stderr) = run_in(dir.path(), case);
        assert_eq!(code, 2, "{case}: {stderr}");
        assert!(stderr.contains(needle), "{case}: {stderr}");
    }
    assert_eq!(files_in(dir.path()), ["gnss.csv", "imu.csv", "p.toml"]);
}

// A record whose temp_c is not a temperature a sensor is characterised at is refused, named.
#[test]
fn a_record_at_an_impossible_temperature_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    for (name, temp_c) in [("cold.csv", -300.0), ("hot.csv", 1e6)] {
        write_file(dir.path(), name, &static_record(3000, temp_c));
        let (code, _, stderr) = run_in(dir.path(), &format!("characterize @{name} --out @b.json"));
        assert_eq!(code, 1, "{stderr}");
        assert!(
            stderr.contains(name) && stderr.contains("temp_c"),
            "{stderr}"
        );
    }
    assert!(!dir.path().join("b.json").exists());
}

// `thermonav allan FILE --json | true`: stdout is closed before the command writes; it must
// end quietly, not panic with "failed printing to stdout".
#[test]
fn a_closed_stdout_ends_the_command_quietly() {
    let dir = tempfile::tempdir().unwrap();
    let file = write_file(dir.path(), "a.csv", &static_record(4000, 20.0));
    for command in [
        ["allan", "--json"],
        ["inspect", "--json"],
        ["inspect", "--quiet"],
    ] {
        let mut child = Command::new(env!("CARGO_BIN_EXE_thermonav"))
            .args([command[0], arg(&file), command[1]])
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        drop(child.stdout.take());
        let output = child.wait_with_output().unwrap();
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(!stderr.contains("panicked"), "{command:?}: {stderr}");
        assert_eq!(output.status.code(), Some(0), "{command:?}: {stderr}");
    }
}

// Memory bounded by the data: an endless input (`/dev/zero`) or a large sparse file without a
// single newline is refused after a bounded read (documents: 64 MiB; lines: 1 MiB), never read
// whole.
#[test]
fn endless_and_newline_free_inputs_are_refused_after_a_bounded_read() {
    let dir = tempfile::tempdir().unwrap();
    let sparse = dir.path().join("sparse.csv");
    std::fs::File::create(&sparse)
        .unwrap()
        .set_len(100 << 20)
        .unwrap();
    let cases = [
        ("bank show /dev/zero", "larger than 64 MiB"),
        // inspect reads a file twice (its header, then its rows), so it refuses any file that
        // is not regular before reading a byte.
        ("inspect /dev/zero", "not a regular file"),
        ("allan /dev/zero", "line longer than"),
        ("simulate profile --out @p.toml", ""),
        ("bank show @sparse.csv", "larger than 64 MiB"),
        ("allan @sparse.csv", "sparse.csv"),
        (
            "filter @sparse.csv --cutoff-hz 1 --out @f.csv",
            "sparse.csv",
        ),
    ];
    for (case, needle) in cases {
        let (code, _, stderr) = run_in(dir.path(), case);
        if needle.is_empty() {
            assert_eq!(code, 0, "{case}: {stderr}");
            continue;
        }
        assert_eq!(code, 1, "{case}: {stderr}");
        assert!(stderr.contains(needle), "{case}: {stderr}");
    }
    let (code, _, stderr) = run_in(dir.path(), "simulate vessel --profile /dev/zero --out @v");
    assert_eq!(code, 1, "{stderr}");
    assert!(!dir.path().join("v").exists());
}

// An AR order whose fit would take minutes (cost samples × order²: order 500 on 60 000
// samples took 45 s) is refused as a usage error before the file is read.
#[test]
fn an_ar_order_above_the_limit_is_refused_before_reading() {
    let dir = tempfile::tempdir().unwrap();
    for words in [
        "ar @missing.csv --order 500",
        "ar @missing.csv --order auto --max-order 101",
    ] {
        let (status, _, stderr) = run_in(dir.path(), words);
        assert_eq!(status, 2, "{words}: {stderr}");
        assert!(stderr.contains("1 to 100"), "{words}: {stderr}");
        assert!(!stderr.contains("missing.csv"), "{words}: {stderr}");
    }
}

// `filter --out D/bank` writes its record to D/bank.json: an existing D/bank.json that is
// not a record (here a bank) is refused before anything is read or written, while the
// record of an earlier run to the same --out is replaced as before.
#[test]
fn a_filter_record_never_overwrites_a_file_that_is_not_one() {
    let dir = tempfile::tempdir().unwrap();
    write_file(dir.path(), "in.csv", &static_record(4000, 20.0));
    let bank = write_file(
        dir.path(),
        "bank.json",
        "{\"version\": 2, \"entries\": []}\n",
    );
    let words = "filter @in.csv --cutoff-hz 5 --transition-hz 2 --out @bank";
    let (status, _, stderr) = run_in(dir.path(), words);
    assert_eq!(status, 2, "{stderr}");
    assert!(stderr.contains("is not a thermonav record"), "{stderr}");
    assert_eq!(
        std::fs::read_to_string(&bank).unwrap(),
        "{\"version\": 2, \"entries\": []}\n"
    );
    assert!(!dir.path().join("bank").exists());
    let again = "filter @in.csv --cutoff-hz 5 --transition-hz 2 --out @out.csv";
    for _ in 0..2 {
        let (status, _, stderr) = run_in(dir.path(), again);
        assert_eq!(status, 0, "{stderr}");
    }
}

/// The hidden temporary files (`.NAME.XXXXXX.tmp`) in `dir`.
fn temporaries_in(dir: &Path) -> Vec<String> {
    if !dir.exists() {
        return Vec::new();
    }
    files_in(dir)
        .into_iter()
        .filter(|n| n.starts_with('.') && n.ends_with(".tmp"))
        .collect()
}

// Issue 20: SIGINT or SIGTERM while `simulate chamber` writes a record (a 70 MB file takes
// seconds) ends it with 128 + the signal and no hidden temporary file left; the records
// already renamed into place are whole.
#[test]
fn a_signal_during_a_write_leaves_no_temporary_file() {
    for (signal, code) in [("TERM", 143), ("INT", 130)] {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("tc");
        let mut child = Command::new(env!("CARGO_BIN_EXE_thermonav"))
            .args([
                "simulate",
                "chamber",
                "--out",
                arg(&out),
                "--duration-s",
                "7200",
            ])
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        let started = std::time::Instant::now();
        while temporaries_in(&out).is_empty() && started.elapsed().as_secs() < 60 {
            std::thread::sleep(std::time::Duration::from_millis(20));
        }
        assert!(
            !temporaries_in(&out).is_empty(),
            "no record was being written"
        );
        let pid = child.id().to_string();
        let killed = Command::new("kill")
            .args([&format!("-{signal}"), &pid])
            .status();
        assert!(killed.unwrap().success());
        let status = child.wait().unwrap();
        assert_eq!(status.code(), Some(code), "SIG{signal}");
        assert_eq!(temporaries_in(&out), Vec::<String>::new(), "SIG{signal}");
    }
}

// Issue 20: a process substitution (`<(cat f)`) is a pipe, which the commands that read their
// first bytes to tell the format cannot read again: they say so, naming it; a command that
// reads once (`allan`) takes it.
#[test]
fn a_process_substitution_is_refused_by_commands_that_read_twice_and_read_by_the_others() {
    let dir = tempfile::tempdir().unwrap();
    let file = write_file(dir.path(), "r.csv", &static_record(6000, 20.0));
    let bin = env!("CARGO_BIN_EXE_thermonav");
    let run = |command: &str| {
        let line = format!("{bin} {command} <(cat {})", file.display());
        let output = Command::new("bash")
            .args(["-c", &line])
            .current_dir(dir.path())
            .output();
        outcome(&output.unwrap())
    };
    for command in [
        "inspect",
        "convert --out o.csv",
        "characterize --temperature-c 20 --out b --sweep",
    ] {
        let command = match command.strip_suffix(" --sweep") {
            Some(head) => format!("{head} {} --sweep", file.display()),
            None => command.to_string(),
        };
        let (status, _, stderr) = run(&command);
        assert_eq!(status, 1, "{command}: {stderr}");
        assert!(
            stderr.contains("/dev/fd/") && stderr.contains("not a regular file"),
            "{command}: {stderr}"
        );
    }
    let (status, stdout, stderr) = run("allan --json");
    assert_eq!(status, 0, "{stderr}");
    assert!(stdout.contains("\"channels\""), "{stdout}");
}

// Issue 20: a stuck sensor (one channel the same value in every sample) is refused by
// characterize, in memory and streamed, naming the file and the channel, instead of being
// given a Gauss-Markov model fitted to rounding noise.
#[test]
fn a_stuck_channel_is_refused_by_characterize() {
    let dir = tempfile::tempdir().unwrap();
    let text = static_record(12_000, 20.0);
    let mut lines = text.lines();
    let mut stuck = format!("{}\n", lines.next().unwrap());
    for line in lines {
        let mut fields: Vec<&str> = line.split(',').collect();
        fields[2] = "0.0025";
        stuck.push_str(&(fields.join(",") + "\n"));
    }
    write_file(dir.path(), "stuck.csv", &stuck);
    for reading in ["in-memory", "streaming"] {
        let words = format!("characterize @stuck.csv --reading {reading} --out @bank.json");
        let (status, _, stderr) = run_in(dir.path(), &words);
        assert_eq!(status, 1, "{reading}: {stderr}");
        assert!(
            stderr.contains("stuck.csv") && stderr.contains("channel gy is constant (0.0025"),
            "{stderr}"
        );
        assert!(!dir.path().join("bank.json").exists());
    }
}

/// `path`'s CSV with the rows (not the header) for which `drop` holds left out.
fn without_rows(path: &Path, drop: impl Fn(&[&str]) -> bool) -> String {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let mut kept = format!("{}\n", lines.next().unwrap());
    for line in lines.filter(|l| !drop(&l.split(',').collect::<Vec<_>>())) {
        kept.push_str(&format!("{line}\n"));
    }
    kept
}

// Issue 20: a 60 s hole in the IMU record was crossed in one step on a held rate, with most
// later fixes rejected and no word. Both navigation commands now refuse a gap longer than
// --max-imu-gap-s (1 s by default), naming the IMU file and where the gap is, before any
// output; a larger limit bridges it as documented.
#[test]
fn an_imu_gap_longer_than_the_limit_is_refused_naming_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let (bank, vessel) = crate::navigation::inputs(dir.path());
    let t_s = |f: &[&str]| f[0].parse::<f64>().unwrap();
    let holed = without_rows(&vessel.join("imu.csv"), |f| {
        (100.0..160.0).contains(&t_s(f))
    });
    write_file(dir.path(), "holed.csv", &holed);
    std::fs::copy(vessel.join("gnss.csv"), dir.path().join("gnss.csv")).unwrap();
    std::fs::copy(
        vessel.join("reference.csv"),
        dir.path().join("reference.csv"),
    )
    .unwrap();
    assert_eq!(bank, dir.path().join("bank.json"));
    let before = files_in(dir.path());
    let common = "--imu @holed.csv --gnss @gnss.csv --bank @bank.json";
    for words in [
        format!("integrate {common} --out @sol.csv"),
        format!("evaluate {common} --reference @reference.csv --outages 170+10 --out @eval"),
    ] {
        let (status, stdout, stderr) = run_in(dir.path(), &words);
        assert_eq!(status, 1, "{words}: {stderr}");
        assert!(stdout.is_empty());
        assert!(
            stderr.contains("holed.csv: the IMU record has a gap of 60.0"),
            "{stderr}"
        );
        assert!(stderr.contains("--max-imu-gap-s"), "{stderr}");
        assert_eq!(files_in(dir.path()), before, "{words}");
    }
    // A million periodic outages over 240 s of reference: refused at once, not drawn.
    let words = "plot trajectory @reference.csv --outages every:10,5,20,1000000 --out @t.svg";
    let (status, _, stderr) = run_in(dir.path(), words);
    assert_eq!(status, 2, "{stderr}");
    assert!(stderr.contains("is not inside the data"), "{stderr}");
    assert_eq!(files_in(dir.path()), before);
    let words = format!("integrate {common} --out @sol.csv --max-imu-gap-s 61");
    let (status, _, stderr) = run_in(dir.path(), &words);
    assert_eq!(status, 0, "{stderr}");
    let (status, _, stderr) = run_in(dir.path(), &format!("{words} --max-imu-gap-s 0"));
    assert_eq!(status, 2, "{stderr}");
}

// Issue 20: the poles. GNSS fixes at -90° ran to -90.0094° with NIS 14134 and exit 0, and a
// motion from 88.99° N wrote latitudes of 90.33°. thermonav navigates within ±89° (the NED
// mechanisation divides by cos φ): both are refused, naming the file, with nothing written.
#[test]
fn positions_beyond_the_navigable_latitudes_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let (bank, vessel) = crate::navigation::inputs(dir.path());
    let gnss = std::fs::read_to_string(vessel.join("gnss.csv")).unwrap();
    let mut polar = String::new();
    for (k, line) in gnss.lines().enumerate() {
        let mut fields: Vec<&str> = line.split(',').collect();
        if k > 0 {
            fields[1] = "-90";
        }
        polar.push_str(&(fields.join(",") + "\n"));
    }
    write_file(dir.path(), "polar.csv", &polar);
    let words = format!(
        "integrate --imu {} --gnss @polar.csv --bank {} --out @sol.csv",
        arg(&vessel.join("imu.csv")),
        arg(&bank)
    );
    let (status, _, stderr) = run_in(dir.path(), &words);
    assert_eq!(status, 1, "{stderr}");
    assert!(
        stderr.contains("polar.csv: the GNSS fix at t = 1.000 s is at latitude -90"),
        "{stderr}"
    );
    assert!(!dir.path().join("sol.csv").exists());
    let motion = "start = { lat_deg = 88.99, lon_deg = 10.0, h_m = 0.0 }\n\
                  initial_speed_m_s = 30.0\n\n[[segment]]\nduration_s = 120.0\n";
    write_file(dir.path(), "north.toml", motion);
    let (status, _, stderr) = run_in(
        dir.path(),
        "simulate vessel --motion @north.toml --out @north --seed 1",
    );
    assert_eq!(status, 1, "{stderr}");
    assert!(
        stderr.contains("north.toml: the motion reaches latitude 89.0000° at t ="),
        "{stderr}"
    );
    assert!(stderr.contains("within ±89°"), "{stderr}");
    assert!(!dir.path().join("north").join("imu.csv").exists());
}

// Issue 20: a bank edited by hand with a negative σ was read, and reported later as a bad
// correlation time. Every value of every entry is checked on reading, and the message names
// the entry, the channel and the field: the optional gmwm family's too (its σ reaches a run
// with `--model gmwm`; it may be 0, a composite with no slow process), which was read
// unchecked before.
#[test]
fn a_bank_value_that_cannot_be_is_named_on_reading() {
    let dir = tempfile::tempdir().unwrap();
    let (bank, _) = crate::navigation::inputs(dir.path());
    let text = std::fs::read_to_string(&bank).unwrap();
    let spoil = |key: &str| text.replacen(key, &format!("{key}-"), 1);
    let gmwm = text.find("\"gmwm\"").expect("the bank holds gmwm models");
    let sigma = gmwm + text[gmwm..].find("\"sigma\": ").unwrap() + "\"sigma\": ".len();
    let end = sigma + text[sigma..].find([',', '\n']).unwrap();
    let gmwm_negative = format!("{}-1e-3{}", &text[..sigma], &text[end..]);
    for (field, bad, expected) in [
        (
            "gauss_markov.ar_based.sigma",
            spoil("\"sigma\": "),
            "a finite number > 0",
        ),
        ("ar.dt_s", spoil("\"dt_s\": "), "a finite number > 0"),
        (
            "gauss_markov.gmwm.sigma",
            gmwm_negative,
            "a finite number >= 0",
        ),
    ] {
        assert_ne!(bad, text);
        write_file(dir.path(), "spoiled.json", &bad);
        let (status, _, stderr) = run_in(dir.path(), "bank show @spoiled.json");
        assert_eq!(status, 1, "{stderr}");
        assert!(stderr.contains("spoiled.json: the entry at"), "{stderr}");
        assert!(
            stderr.contains(&format!("channel gx: {field} = -")),
            "{stderr}"
        );
        assert!(stderr.contains(&format!("expected {expected}")), "{stderr}");
    }
}

// Issue 20: a 254-byte output name worked for the CSV but its record `NAME.json` (259 bytes)
// could not be created, leaving the CSV written and the command failed. Every output's name
// is checked before anything is read or written.
#[test]
fn an_output_name_too_long_for_its_sidecar_is_refused_before_writing() {
    let dir = tempfile::tempdir().unwrap();
    write_file(dir.path(), "in.csv", &static_record(2000, 20.0));
    let name = format!("{}.csv", "a".repeat(250));
    let words = format!("filter @in.csv --cutoff-hz 10 --out @{name}");
    let (status, _, stderr) = run_in(dir.path(), &words);
    assert_eq!(status, 2, "{stderr}");
    assert!(
        stderr.contains("has a file name of 259 bytes; file systems hold at most 255"),
        "{stderr}"
    );
    assert_eq!(files_in(dir.path()), vec!["in.csv".to_string()]);
}
