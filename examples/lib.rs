//! The examples' package: the programs are its examples (`cargo run
//! --release --example NAME`, see README.md); this library holds what
//! several of them share.

use anyhow::Context as _;
use tritri_geom::scene::load::{load_object, Pose, SceneObject};
use tritri_rtl::broad_phase::list_pass_machine::PASS_DATA_BITS;

pub use tritri_cosim::dram_query::{VERSA_GBYTES, VERSA_LINK_GBYTES};

/// The median of `runs` runs of `f`, each timed.
pub fn median_time(runs: usize, mut f: impl FnMut()) -> std::time::Duration {
    let mut times: Vec<_> = (0..runs.max(1))
        .map(|_| {
            let started = std::time::Instant::now();
            f();
            started.elapsed()
        })
        .collect();
    times.sort();
    times[times.len() / 2]
}

/// The value after the option `name` in `args`, both taken out (`None`
/// without the option); an error saying it takes `what` when no value
/// follows.
pub fn take_option(
    args: &mut Vec<String>,
    name: &str,
    what: &str,
) -> anyhow::Result<Option<String>> {
    match args.iter().position(|a| a == name) {
        Some(i) if i + 1 < args.len() => {
            let value = args.remove(i + 1);
            args.remove(i);
            Ok(Some(value))
        }
        Some(_) => anyhow::bail!("{name} takes {what}"),
        None => Ok(None),
    }
}

/// The port width after `--data-bits` in `args`, both taken out
/// (`default` without the option); an error naming the value when the
/// pass units are not built for it.
pub fn take_data_bits(args: &mut Vec<String>, default: usize) -> anyhow::Result<usize> {
    let widths = PASS_DATA_BITS.map(|b| b.to_string()).join(", ");
    match take_option(args, "--data-bits", &format!("one of {widths}"))? {
        None => Ok(default),
        Some(bits) => bits
            .parse()
            .ok()
            .filter(|b| PASS_DATA_BITS.contains(b))
            .with_context(|| format!("--data-bits {bits:?}: the port is {widths} bits wide")),
    }
}

/// The two objects of `A B [SCALE_B TX TY TZ]` (none: the built-in torus
/// and sphere), B scaled and moved; `usage` names the program in the error.
pub fn scene_objects(args: &[String], usage: &str) -> anyhow::Result<(SceneObject, SceneObject)> {
    let number = |s: &str| -> anyhow::Result<f64> {
        s.parse().with_context(|| format!("{s:?} is not a number"))
    };
    let (a, b, scale, pose) = match args {
        [] => ("@torus", "@sphere", 1.0, [0.0; 3]),
        [a, b] => (a.as_str(), b.as_str(), 1.0, [0.0; 3]),
        [a, b, s, x, y, z] => (
            a.as_str(),
            b.as_str(),
            number(s)?,
            [number(x)?, number(y)?, number(z)?],
        ),
        _ => anyhow::bail!("usage: {usage} [A B [SCALE_B TX TY TZ]]"),
    };
    let a = load_object(a, 8)?;
    let b = load_object(b, 8)?
        .scaled(scale)
        .posed(&Pose::translation(pose));
    Ok((a, b))
}
