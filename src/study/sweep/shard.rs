//! Shards: a sweep cut into N parts that run anywhere (the tasks of a Slurm job array, separate
//! machines), each into its own folder `OUT/parts/I-of-N` ([`super::merge`] makes them one
//! sweep again). Case `id` belongs to shard `id mod N`: neighbouring cases (the samples of one
//! wall and motion, often of like cost) spread over the shards.

use crate::error::Error;
use std::path::{Path, PathBuf};

/// Part `index` of `count` (0-based).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// Which part.
    pub index: usize,
    /// How many parts.
    pub count: usize,
}

/// The most parts a sweep is cut into (Slurm's own limit on an array is lower).
pub const MAX_SHARDS: usize = 1_000_000;

impl std::fmt::Display for Shard {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

fn shard_error(rule: String) -> Error {
    Error::Option {
        option: "--shard".into(),
        rule,
    }
}

impl Shard {
    /// Part `index` of `count`, checked.
    pub fn new(index: usize, count: usize) -> Result<Shard, Error> {
        if count == 0 || count > MAX_SHARDS || index >= count {
            return Err(shard_error(format!(
                "part {index} of {count}: give I/N with N from 1 to {MAX_SHARDS} and I from 0 to N-1"
            )));
        }
        Ok(Shard { index, count })
    }

    /// Reads `I/N`, or `auto`: the part from the Slurm job array this process runs in, read
    /// from the variables `env` gives (`SLURM_ARRAY_TASK_ID`, `_MIN`, `_STEP`, `_COUNT`).
    pub fn parse(text: &str, env: impl Fn(&str) -> Option<String>) -> Result<Shard, Error> {
        if text == "auto" {
            return Shard::from_slurm(env);
        }
        let parsed = text
            .split_once('/')
            .and_then(|(i, n)| Some((i.trim().parse().ok()?, n.trim().parse().ok()?)));
        let (index, count) = parsed.ok_or_else(|| {
            shard_error(format!(
                "\"{text}\": give I/N (part I of N, from 0: 0/3, 1/3, 2/3) or auto (the Slurm \
                 array task)"
            ))
        })?;
        Shard::new(index, count)
    }

    /// The part of a Slurm array task: its place among the array's task ids.
    fn from_slurm(env: impl Fn(&str) -> Option<String>) -> Result<Shard, Error> {
        let var = |name: &str, default: Option<usize>| -> Result<usize, Error> {
            match env(name) {
                Some(v) => v.trim().parse().map_err(|_| {
                    shard_error(format!("auto: {name} is \"{v}\", not a whole number"))
                }),
                None => default.ok_or_else(|| {
                    shard_error(format!(
                        "auto: {name} is not set (this is not a Slurm array task): give I/N"
                    ))
                }),
            }
        };
        let id = var("SLURM_ARRAY_TASK_ID", None)?;
        let min = var("SLURM_ARRAY_TASK_MIN", None)?;
        let step = var("SLURM_ARRAY_TASK_STEP", Some(1))?.max(1);
        let count = var("SLURM_ARRAY_TASK_COUNT", None)?;
        if id < min || (id - min) % step != 0 {
            return Err(shard_error(format!(
                "auto: task {id} is not on the array's range from {min} in steps of {step}: \
                 submit the array as --array=0-{} or give I/N",
                count.saturating_sub(1)
            )));
        }
        Shard::new((id - min) / step, count)
    }

    /// Whether case `id` is in this part.
    pub fn contains(&self, id: usize) -> bool {
        id % self.count == self.index
    }

    /// The number of this part's cases in a sweep of `cases`.
    pub fn len(&self, cases: usize) -> usize {
        (cases + self.count - 1 - self.index) / self.count
    }

    /// Whether this part of a sweep of `cases` has none (more parts than cases).
    pub fn is_empty(&self, cases: usize) -> bool {
        self.len(cases) == 0
    }

    /// This part's folder in the output directory `out`.
    pub fn folder(&self, out: &Path) -> PathBuf {
        parts(out).join(format!("{}-of-{}", self.index, self.count))
    }
}

/// Where the shards of a sweep into `out` write their parts.
pub fn parts(out: &Path) -> PathBuf {
    out.join("parts")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every case falls in exactly one part, and `len` counts them.
    #[test]
    fn parts_cover_every_case_once() {
        for count in 1..8 {
            for cases in 0..30 {
                let mut seen = vec![0; cases];
                for index in 0..count {
                    let s = Shard::new(index, count).unwrap();
                    let ids: Vec<usize> = (0..cases).filter(|&id| s.contains(id)).collect();
                    assert_eq!(ids.len(), s.len(cases), "{s} of {cases}");
                    ids.iter().for_each(|&id| seen[id] += 1);
                }
                assert!(seen.iter().all(|&n| n == 1));
            }
        }
    }

    /// `I/N` and Slurm's array variables read as the part they name; anything else is refused
    /// with what to give.
    #[test]
    fn shards_read_from_text_and_from_slurm() {
        let none = |_: &str| None;
        assert_eq!(
            Shard::parse("2/3", none).unwrap(),
            Shard { index: 2, count: 3 }
        );
        for bad in ["3/3", "0/0", "1", "a/b", "-1/3", "1/2000000"] {
            let e = Shard::parse(bad, none).unwrap_err().to_string();
            assert!(
                e.starts_with("--shard: ") && e.contains("I/N"),
                "{bad}: {e}"
            );
        }
        let slurm = |id: &'static str, step: Option<&'static str>| {
            move |name: &str| match name {
                "SLURM_ARRAY_TASK_ID" => Some(id.to_string()),
                "SLURM_ARRAY_TASK_MIN" => Some("1".into()),
                "SLURM_ARRAY_TASK_STEP" => step.map(String::from),
                "SLURM_ARRAY_TASK_COUNT" => Some("4".into()),
                _ => None,
            }
        };
        assert_eq!(
            Shard::parse("auto", slurm("3", None)).unwrap(),
            Shard { index: 2, count: 4 }
        );
        assert_eq!(
            Shard::parse("auto", slurm("7", Some("2"))).unwrap(),
            Shard { index: 3, count: 4 }
        );
        let e = Shard::parse("auto", slurm("4", Some("2")))
            .unwrap_err()
            .to_string();
        assert!(e.contains("not on the array's range"), "{e}");
        let e = Shard::parse("auto", none).unwrap_err().to_string();
        assert!(e.contains("SLURM_ARRAY_TASK_ID is not set"), "{e}");
    }
}
