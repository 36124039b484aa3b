//! `--shard auto`: the slice of a sweep a Slurm array task computes, from the environment Slurm
//! sets in each task of an array job (`sbatch --array=A-B[:S]`): `SLURM_ARRAY_TASK_ID`,
//! `SLURM_ARRAY_TASK_COUNT`, and, to number tasks from 1 whatever the array's first index and
//! step, `SLURM_ARRAY_TASK_MIN` and `SLURM_ARRAY_TASK_STEP` when set. Task k of N (in index
//! order) computes shard k/N, so concatenating the tasks' outputs in index order reproduces the
//! unsharded sweep.

use crate::analysis::grid::Shard;
use crate::error::{Error, Result};

/// The shard `--shard TEXT` names: `auto` from the Slurm environment, else `I/N`.
pub fn shard(text: &str) -> Result<Shard> {
    if text.trim() == "auto" {
        from_env(|name| std::env::var(name).ok())
    } else {
        Shard::parse(text)
    }
}

/// The shard of this array task, from `env` (the process environment, or a test's).
pub fn from_env(env: impl Fn(&str) -> Option<String>) -> Result<Shard> {
    let number = |name: &str| -> Result<Option<usize>> {
        env(name)
            .map(|v| {
                v.trim().parse::<usize>().map_err(|_| {
                    Error::usage(format!(
                        "--shard auto: {name} = '{v}' is not a non-negative whole number"
                    ))
                })
            })
            .transpose()
    };
    let (id, count) =
        match (
            number("SLURM_ARRAY_TASK_ID")?,
            number("SLURM_ARRAY_TASK_COUNT")?,
        ) {
            (Some(id), Some(count)) => (id, count),
            _ => return Err(Error::usage(
                "--shard auto takes the slice from a Slurm array job, but SLURM_ARRAY_TASK_ID and \
                 SLURM_ARRAY_TASK_COUNT are not both set: run it inside `sbatch --array=…`, or \
                 give the slice as --shard I/N",
            )),
        };
    let min = number("SLURM_ARRAY_TASK_MIN")?.unwrap_or(0);
    let step = number("SLURM_ARRAY_TASK_STEP")?.unwrap_or(1);
    if step == 0 {
        return Err(Error::usage(
            "--shard auto: SLURM_ARRAY_TASK_STEP = 0; an array's step is at least 1 (`sbatch \
             --array=A-B:S`)",
        ));
    }
    let offset = id
        .checked_sub(min)
        .filter(|d| d % step == 0)
        .map(|d| d / step);
    match offset {
        Some(k) if k < count => Shard::parse(&format!("{}/{count}", k + 1)),
        _ => Err(Error::usage(format!(
            "--shard auto: SLURM_ARRAY_TASK_ID = {id} is not one of the {count} tasks \
             (SLURM_ARRAY_TASK_COUNT) from SLURM_ARRAY_TASK_MIN = {min} in steps of \
             SLURM_ARRAY_TASK_STEP = {step}"
        ))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn env<'a>(vars: &'a [(&'a str, &'a str)]) -> impl Fn(&str) -> Option<String> + 'a {
        move |name| {
            vars.iter()
                .find(|(k, _)| *k == name)
                .map(|(_, v)| v.to_string())
        }
    }

    #[test]
    fn array_tasks_number_their_shards_from_one() {
        let s = from_env(env(&[
            ("SLURM_ARRAY_TASK_ID", "0"),
            ("SLURM_ARRAY_TASK_COUNT", "4"),
        ]));
        assert_eq!(s.unwrap(), Shard { index: 1, count: 4 });
        let s = from_env(env(&[
            ("SLURM_ARRAY_TASK_ID", "7"),
            ("SLURM_ARRAY_TASK_COUNT", "4"),
            ("SLURM_ARRAY_TASK_MIN", "1"),
            ("SLURM_ARRAY_TASK_STEP", "2"),
        ]));
        assert_eq!(s.unwrap(), Shard { index: 4, count: 4 });
    }

    #[test]
    fn outside_an_array_job_the_error_says_so() {
        let e = from_env(env(&[])).unwrap_err().to_string();
        assert!(
            e.contains("SLURM_ARRAY_TASK_ID") && e.contains("--shard I/N"),
            "{e}"
        );
        let e = from_env(env(&[
            ("SLURM_ARRAY_TASK_ID", "5"),
            ("SLURM_ARRAY_TASK_COUNT", "4"),
        ]))
        .unwrap_err()
        .to_string();
        assert!(e.contains("= 5") && e.contains("4 tasks"), "{e}");
        let e = from_env(env(&[
            ("SLURM_ARRAY_TASK_ID", "x"),
            ("SLURM_ARRAY_TASK_COUNT", "4"),
        ]))
        .unwrap_err()
        .to_string();
        assert!(e.contains("'x'"), "{e}");
    }
}
