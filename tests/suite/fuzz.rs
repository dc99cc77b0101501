//! Fuzzing on the stable toolchain (issue 34; cargo-fuzz needs nightly, which a fresh machine
//! lacks): structure-aware generators of walls (RON) and records (AT2, COSMOS, plain text),
//! byte-level mutation of the shipped files, and command lines for the binary. Every input is a
//! pure function of (seed, index), so a failure is replayed by its index alone. On every input:
//! no panic, and an error or a run; on every run: finite outputs, the energy balance closed, no
//! block through its neighbour, and no input taking more than a few seconds.
//!
//! The suite runs a short campaign (`PIRQA_FUZZ_INPUTS`, default 3,000); `PIRQA_FUZZ_ONLY=i` runs
//! and prints input i alone; docs/reliability.md gives the command of the 10^6-input run and
//! what it found.

use pirqa::motion::formats::{detect, ReadOptions};
use pirqa::rng::Rng;
use pirqa::{Model, Motion, RunSettings, Sine};
use std::collections::BTreeMap;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};

/// The campaign's seed: change it to explore, keep it to replay.
const SEED: u64 = 0x5049_5251_4131_3334;
/// An input that takes longer than this is a finding (a hang in the making).
const SLOW: Duration = Duration::from_secs(5);
/// One input in this many is a command line run by the binary (a process each).
const COMMAND_LINE_EVERY: u64 = 200;

/// Values a number field is given: ordinary ones, or with probability `hostile` hostile ones.
fn number(rng: &mut Rng, hostile_p: f64, ordinary: (f64, f64)) -> String {
    let hostile = [
        "0",
        "-1",
        "-0.5",
        "1e-300",
        "1e300",
        "5e-324",
        "1.7976931348623157e308",
        "NaN",
        "inf",
        "-inf",
        "1e20",
        "1e-20",
        "\"1\"",
        "()",
        "",
        "0x10",
        "1_000",
        "9999999999999999999999",
    ];
    if rng.uniform() < hostile_p {
        hostile[pick(rng, hostile.len())].to_string()
    } else {
        // Always with a decimal point: RON reads `1` as an integer, not a float.
        let (lo, hi) = ordinary;
        format!("{:?}", lo + (hi - lo) * rng.uniform())
    }
}

fn pick(rng: &mut Rng, k: usize) -> usize {
    ((rng.uniform() * k as f64) as usize).min(k - 1)
}

/// A wall file made from its grammar: rows or rectangles with random sizes, friction, density,
/// restitution and joint keys, some of them hostile.
fn grammar_wall(rng: &mut Rng, h: f64) -> String {
    let mut fields = vec![
        "version: 1".to_string(),
        format!("thickness_m: {}", number(rng, h, (0.2, 1.5))),
        format!("density_kg_m3: {}", number(rng, h, (1500.0, 3000.0))),
        format!("friction: {}", number(rng, h, (0.1, 0.9))),
    ];
    if rng.uniform() < 0.5 {
        fields.push(format!("restitution: {}", number(rng, h, (0.0, 1.0))));
    }
    if rng.uniform() < 0.5 {
        let rows: Vec<String> = (0..1 + pick(rng, 3))
            .map(|_| {
                let widths: Vec<String> = (0..1 + pick(rng, 6))
                    .map(|_| format!("(width_m: {})", number(rng, h, (0.2, 1.5))))
                    .collect();
                let x = if rng.uniform() < 0.3 {
                    format!(", x_m: {}", number(rng, h, (0.0, 0.5)))
                } else {
                    String::new()
                };
                format!(
                    "(height_m: {}{x}, blocks: [{}])",
                    number(rng, h, (0.2, 1.0)),
                    widths.join(", ")
                )
            })
            .collect();
        fields.push(format!("rows: [{}]", rows.join(", ")));
    } else {
        // Courses of blocks side by side (a gap now and then), each course on the one below:
        // mostly walls that stand, so that the hostile numbers among them are what is tested.
        let mut rects = Vec::new();
        let mut y = 0.0;
        for _ in 0..1 + pick(rng, 3) {
            let height = 0.2 + 0.8 * rng.uniform();
            let mut x = 0.3 * rng.uniform();
            for _ in 0..1 + pick(rng, 3) {
                let width = 0.3 + rng.uniform();
                let mut value = |v: f64| number(rng, h, (v, v));
                rects.push(format!(
                    "(x_m: {}, y_m: {}, width_m: {}, height_m: {})",
                    value(x),
                    value(y),
                    value(width),
                    value(height)
                ));
                x += width
                    + if rng.uniform() < 0.3 {
                        0.01 * rng.uniform()
                    } else {
                        0.0
                    };
            }
            y += height;
        }
        fields.push(format!("rectangles: [{}]", rects.join(", ")));
    }
    if rng.uniform() < 0.3 {
        let names = ["B1", "B2", "B3", "B4", "ground", "B9", "", "B1/B2"];
        let keys: Vec<String> = (0..1 + pick(rng, 3))
            .map(|_| {
                format!(
                    "\"{}/{}\": {}",
                    names[pick(rng, names.len())],
                    names[pick(rng, names.len())],
                    number(rng, h, (0.1, 0.9))
                )
            })
            .collect();
        fields.push(format!("joint_friction: {{{}}}", keys.join(", ")));
    }
    format!("({})", fields.join(", "))
}

/// A file changed byte by byte: flips, deletions, insertions, a duplicated or dropped line, a
/// cut, a byte-order mark.
fn mutate(rng: &mut Rng, text: &str) -> Vec<u8> {
    let mut bytes = text.as_bytes().to_vec();
    for _ in 0..1 + pick(rng, 4) {
        if bytes.is_empty() {
            break;
        }
        let at = pick(rng, bytes.len());
        match pick(rng, 7) {
            0 => bytes[at] ^= 1 << pick(rng, 8),
            1 => {
                bytes.remove(at);
            }
            2 => bytes.insert(at, b"0123456789.-e,:()[]\"\n \x00\xff"[pick(rng, 21)]),
            3 => bytes.truncate(at),
            4 => {
                let line: Vec<u8> = bytes[at..]
                    .iter()
                    .take_while(|&&b| b != b'\n')
                    .copied()
                    .collect();
                bytes.splice(at..at, line.into_iter().chain([b'\n']));
            }
            5 => {
                let end = bytes[at..]
                    .iter()
                    .position(|&b| b == b'\n')
                    .map_or(bytes.len(), |p| at + p);
                bytes.drain(at..end);
            }
            _ => bytes.splice(0..0, [0xef, 0xbb, 0xbf]).for_each(drop),
        }
    }
    bytes
}

/// A plain-text record from its grammar: headers (units, dt) given once, twice or not at all,
/// one or two columns, hostile numbers among the samples.
fn grammar_record(rng: &mut Rng, h: f64) -> String {
    let mut text = String::new();
    for _ in 0..pick(rng, 3) {
        let units = ["g", "gal", "m/s2", "cm/s2", "furlongs", ""];
        text += &format!("# units: {}\n", units[pick(rng, units.len())]);
    }
    for _ in 0..pick(rng, 3) {
        text += &format!("# dt_s: {}\n", number(rng, h, (0.005, 0.02)));
    }
    let two = rng.uniform() < 0.3;
    for k in 0..pick(rng, 400) {
        let a = if rng.uniform() < 0.02 {
            number(rng, h, (-0.5, 0.5))
        } else {
            format!("{}", 0.3 * (rng.uniform() - 0.5))
        };
        if two {
            text += &format!("{},{a}\n", k as f64 * 0.01);
        } else {
            text += &format!("{a}\n");
        }
    }
    text
}

/// A record's AT2 header with its point count and interval replaced.
fn hostile_at2_header(rng: &mut Rng, text: &str) -> String {
    let npts = ["1e30", "1000000000000", "-5", "0", "NaN", "3", "99999999"];
    let dt = ["1e-300", "0", "-0.01", "1e300", ".0100", "NaN"];
    text.replacen(
        "NPTS=",
        &format!(
            "NPTS= {} , DT= {} SEC ",
            npts[pick(rng, npts.len())],
            dt[pick(rng, dt.len())]
        ),
        1,
    )
}

/// What went wrong with one input: a short class (for counting) and the details.
struct Finding {
    class: String,
    detail: String,
}

/// The shipped files the mutations start from.
struct Corpus {
    walls: Vec<String>,
    records: Vec<String>,
}

impl Corpus {
    fn load() -> Corpus {
        let read_dir = |dir: &str, ext: &str| -> Vec<String> {
            let mut paths: Vec<_> = std::fs::read_dir(dir)
                .unwrap()
                .map(|e| e.unwrap().path())
                .filter(|p| p.extension().is_some_and(|e| e == ext))
                .collect();
            paths.sort();
            paths
                .iter()
                .map(|p| std::fs::read_to_string(p).unwrap())
                .collect()
        };
        let mut walls = read_dir("walls", "ron");
        walls.extend(read_dir("walls/inca", "ron"));
        let records = read_dir("records", "AT2");
        Corpus { walls, records }
    }
}

/// One input: a wall and a motion from the generators, run through the library.
fn library_input(corpus: &Corpus, rng: &mut Rng) -> Result<(), Finding> {
    // How hostile this input's numbers are: half clean, so that runs are fuzzed too.
    let h = [0.0, 0.0, 0.02, 0.3][pick(rng, 4)];
    let wall_text = if rng.uniform() < 0.6 {
        grammar_wall(rng, h)
    } else {
        let base = &corpus.walls[pick(rng, corpus.walls.len())];
        if h == 0.0 {
            base.clone()
        } else {
            String::from_utf8_lossy(&mutate(rng, base)).into_owned()
        }
    };
    let motion_kind = pick(rng, 3);
    let record_text = match motion_kind {
        0 => None,
        1 => Some(grammar_record(rng, h)),
        _ => {
            let base = &corpus.records[pick(rng, corpus.records.len())];
            let text = if rng.uniform() < 0.3 {
                hostile_at2_header(rng, base)
            } else {
                base.clone()
            };
            if h == 0.0 {
                Some(text)
            } else {
                Some(String::from_utf8_lossy(&mutate(rng, &text)).into_owned())
            }
        }
    };
    let sine: Vec<f64> = (0..3)
        .map(|k| {
            let ordinary = [(1.0, 6.0), (0.5, 4.0), (0.0, 360.0)][k];
            number(rng, h, ordinary).parse().unwrap_or(f64::NAN)
        })
        .collect();
    let duration = 0.5 + 4.5 * rng.uniform();
    let input = format!(
        "wall:\n{wall_text}\nrecord:\n{}\nsine {sine:?}, {duration} s",
        record_text.as_deref().unwrap_or("(sine)")
    );
    if std::env::var_os("PIRQA_FUZZ_ONLY").is_some() {
        eprintln!("{input}");
    }
    let outcome = catch_unwind(AssertUnwindSafe(|| -> Result<Option<Finding>, String> {
        let model = Model::from_ron_str(&wall_text).map_err(|e| e.to_string())?;
        let motion = match &record_text {
            None => Motion::sine(Sine {
                amplitude_m_s2: sine[0],
                frequency_hz: sine[1],
                phase_rad: pirqa::motion::phase_rad(sine[2]),
                duration_s: duration,
            })
            .map_err(|e| e.to_string())?,
            Some(text) => {
                // What a plain file does not say itself, as the command line would give it.
                let opts = ReadOptions {
                    dt_s: (!text.contains("# dt_s")).then_some(0.01),
                    units: (!text.contains("# units")).then_some(pirqa::units::AccelUnit::G),
                    component: None,
                };
                let format = detect(text);
                let opts = if format.name() == "plain" {
                    opts
                } else {
                    ReadOptions::default()
                };
                Motion::Record(
                    format
                        .read("fuzz", text, &opts)
                        .map_err(|e| e.to_string())?,
                )
            }
        };
        let settings = RunSettings {
            duration_s: Some(duration.min(motion.duration_s().max(0.1))),
            output_dt_s: Some(0.05),
            ..RunSettings::default()
        };
        let response = pirqa::run(&model, &motion, &settings).map_err(|e| e.to_string())?;
        Ok(check_run(&model, &response))
    }));
    match outcome {
        Err(panic) => {
            let message = panic
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| panic.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_default();
            Err(Finding {
                class: format!("panic: {}", message.lines().next().unwrap_or("")),
                detail: input,
            })
        }
        Ok(Err(message)) if message.trim().is_empty() => Err(Finding {
            class: "error without a message".into(),
            detail: input,
        }),
        Ok(Err(_)) => {
            REFUSED.fetch_add(1, Ordering::Relaxed);
            Ok(())
        }
        Ok(Ok(None)) => {
            RAN.fetch_add(1, Ordering::Relaxed);
            Ok(())
        }
        Ok(Ok(Some(f))) => Err(Finding {
            detail: format!("{}\n{input}", f.detail),
            ..f
        }),
    }
}

/// The invariants of a run that went through.
fn check_run(model: &Model, r: &pirqa::Response) -> Option<Finding> {
    let s = &r.summary;
    let e = &s.energy;
    let numbers = s
        .blocks
        .iter()
        .flat_map(|b| {
            [
                b.max_abs_displacement_m,
                b.final_displacement_m,
                b.max_abs_velocity_m_s,
            ]
        })
        .chain([
            e.input_j,
            e.friction_j,
            e.impact_loss_j,
            e.kinetic_j,
            e.residual_j,
        ]);
    if let Some(x) = numbers.into_iter().find(|x| !x.is_finite()) {
        return Some(Finding {
            class: "non-finite output".into(),
            detail: format!("{x} in {s:?}"),
        });
    }
    let scale = e
        .input_j
        .abs()
        .max(e.friction_j.abs())
        .max(e.initial_j.abs())
        .max(1.0);
    if e.residual_j.abs() > 1e-6 * scale {
        return Some(Finding {
            class: "energy balance open".into(),
            detail: format!("residual {} J of {scale} J", e.residual_j),
        });
    }
    // No block through its neighbour (in the plane, while both stand).
    if let Some(h) = &r.history {
        let topo = model.topology();
        for (k, u) in h.displacement_m.iter().enumerate() {
            for j in &topo.vertical {
                let (l, rt) = (j.left.0, j.right.0);
                if s.blocks[l].fell || s.blocks[rt].fell {
                    continue;
                }
                let gap = j.gap_m.to_f64() + u[rt] - u[l];
                if gap < -1e-9 {
                    return Some(Finding {
                        class: "penetration".into(),
                        detail: format!("gap {gap} m at t = {} s", h.time_s[k]),
                    });
                }
            }
        }
    }
    None
}

/// One input: a command line for the binary, options and values drawn from the accepted ones
/// and hostile ones. It must end, within the time allowed, with 0 or a message (exit 1), never
/// a panic (101) or a signal.
fn command_line_input(rng: &mut Rng, scratch: &std::path::Path) -> Result<(), Finding> {
    let walls = [
        "walls/five-block-variable.ron",
        "walls/inca/stela.ron",
        "nowhere.ron",
    ];
    let mut args: Vec<String> = vec!["run".into(), walls[pick(rng, walls.len())].into()];
    let options: [(&str, (f64, f64), &[&str]); 10] = [
        (
            "--sine",
            (1.0, 6.0),
            &["400gal", "0.4g", "4m/s2", "-3m/s2", "5 furlongs"],
        ),
        ("--freq", (0.5, 4.0), &["1", "-1", "0"]),
        ("--duration", (0.5, 5.0), &["1", "-2", "0"]),
        ("--phase", (0.0, 360.0), &["-90", "1e18"]),
        ("--pulse", (1.0, 6.0), &["300gal"]),
        ("--output-dt", (0.01, 0.1), &["1e-9", "0"]),
        (
            "--method",
            (0.0, 0.0),
            &["event", "moreau", "newmark", "regularized", "magic"],
        ),
        ("--model", (0.0, 0.0), &["slide", "auto", "rock", "jelly"]),
        ("--scale", (0.5, 2.0), &["-1", "1e300"]),
        (
            "--record",
            (0.0, 0.0),
            &["records/elcentro1940_ns_peknold_dt0p02_g.AT2", "none.AT2"],
        ),
    ];
    for _ in 0..1 + pick(rng, 5) {
        let (name, ordinary, words) = options[pick(rng, options.len())];
        args.push(name.into());
        args.push(if ordinary.1 > ordinary.0 && rng.uniform() < 0.5 {
            number(rng, 0.2, ordinary)
        } else {
            words[pick(rng, words.len())].to_string()
        });
    }
    if rng.uniform() < 0.5 {
        args.extend(["--out".into(), scratch.to_string_lossy().into_owned()]);
    }
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_pirqa"))
        .args(&args)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let started = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        if started.elapsed() > 4 * SLOW {
            child.kill().unwrap();
            return Err(Finding {
                class: "command line did not end".into(),
                detail: format!("{args:?}"),
            });
        }
        std::thread::sleep(Duration::from_millis(2));
    };
    let mut err = String::new();
    use std::io::Read;
    child
        .stderr
        .take()
        .unwrap()
        .read_to_string(&mut err)
        .unwrap();
    match status.code() {
        Some(0) => Ok(()),
        Some(1) if err.contains("error") && !err.contains("panicked") => Ok(()),
        // clap's own usage errors.
        Some(2) if err.contains("error:") => Ok(()),
        code => Err(Finding {
            class: format!("command line exit {code:?}"),
            detail: format!("{args:?}\n{err}"),
        }),
    }
}

/// Runs inputs `inputs` of the campaign on every core; returns the findings by class with the
/// first input of each (its index and details).
pub fn campaign(inputs: std::ops::Range<u64>) -> BTreeMap<String, (u64, u64, String)> {
    let corpus = Corpus::load();
    let threads = std::thread::available_parallelism().map_or(2, |n| n.get()) as u64;
    let scratch = crate::common::scratch("fuzz");
    // A panic inside the library is caught and counted; its default message would print once
    // per input. Only the campaign's threads are silenced (other tests run beside it).
    let previous = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        if !FUZZING.with(|f| f.get()) {
            previous(info);
        }
    }));
    let found = std::thread::scope(|s| {
        let handles: Vec<_> = (0..threads)
            .map(|w| {
                let (corpus, scratch) = (&corpus, scratch.join(format!("w{w}")));
                s.spawn(move || {
                    FUZZING.with(|f| f.set(true));
                    let mut found: BTreeMap<String, (u64, u64, String)> = BTreeMap::new();
                    for i in (inputs.start + w..inputs.end).step_by(threads as usize) {
                        let mut rng = Rng::new(SEED ^ i.wrapping_mul(0x9e37_79b9_7f4a_7c15));
                        let started = Instant::now();
                        let mut result = if i % COMMAND_LINE_EVERY == COMMAND_LINE_EVERY - 1 {
                            command_line_input(&mut rng, &scratch)
                        } else {
                            library_input(corpus, &mut rng)
                        };
                        if result.is_ok() && started.elapsed() > SLOW {
                            result = Err(Finding {
                                class: "slow input".into(),
                                detail: format!(
                                    "{:?}; see it with PIRQA_FUZZ_ONLY={i}",
                                    started.elapsed()
                                ),
                            });
                        }
                        if let Err(f) = result {
                            let entry = found.entry(f.class).or_insert((0, i, f.detail));
                            entry.0 += 1;
                        }
                    }
                    found
                })
            })
            .collect();
        let mut all: BTreeMap<String, (u64, u64, String)> = BTreeMap::new();
        for h in handles {
            for (class, (n, first, detail)) in h.join().unwrap() {
                let entry = all.entry(class).or_insert((0, first, detail.clone()));
                entry.0 += n;
                if first < entry.1 {
                    (entry.1, entry.2) = (first, detail);
                }
            }
        }
        all
    });
    found
}

/// Inputs that ran to the end, and inputs refused with a message (library inputs).
static RAN: AtomicU64 = AtomicU64::new(0);
static REFUSED: AtomicU64 = AtomicU64::new(0);

thread_local! {
    /// This thread runs the campaign's inputs.
    static FUZZING: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

#[test]
fn a_seeded_fuzz_campaign_finds_nothing() {
    let number = |name: &str| std::env::var(name).ok().and_then(|v| v.parse::<u64>().ok());
    // One input alone, printed: a finding replayed.
    let inputs = match number("PIRQA_FUZZ_ONLY") {
        Some(i) => i..i + 1,
        None => 0..number("PIRQA_FUZZ_INPUTS").unwrap_or(3000),
    };
    let count = inputs.end - inputs.start;
    let started = Instant::now();
    let found = campaign(inputs);
    eprintln!(
        "fuzz: {count} inputs in {:.1} s: {} ran, {} refused with a message, {} classes of finding",
        started.elapsed().as_secs_f64(),
        RAN.load(Ordering::Relaxed),
        REFUSED.load(Ordering::Relaxed),
        found.len()
    );
    let report: Vec<String> = found
        .iter()
        .map(|(class, (n, first, detail))| {
            format!("{class}: {n} inputs, first #{first}:\n{detail}\n")
        })
        .collect();
    assert!(found.is_empty(), "{}", report.join("\n"));
}
