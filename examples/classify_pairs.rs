//! Decide every triangle pair of a file in every arithmetic the library
//! has, and count how each differs from the exact answer.
//!
//! ```sh
//! cargo run --release --example classify_pairs [-- PAIRS_FILE]
//! ```
//!
//! Without a file it reads `examples/data/six_pairs.txt`, whose answers
//! are known (see its comments), and checks that the exact arithmetic
//! gives them: the program fails if that stops being true.

use tritri_geom::arithmetic::{classify, Arithmetic};
use tritri_geom::pairs_io::read_pairs;

/// The answers of data/six_pairs.txt.
const SIX_PAIRS: [bool; 6] = [true, true, true, false, false, true];

fn main() -> anyhow::Result<()> {
    let default = concat!(env!("CARGO_MANIFEST_DIR"), "/data/six_pairs.txt");
    let path = std::env::args()
        .nth(1)
        .unwrap_or_else(|| default.to_string());
    let file = read_pairs(&path)?;
    // A record that cannot be read is an error naming file and line.
    if let Some(error) = file.errors().next() {
        anyhow::bail!("{error}");
    }
    let pairs = file.good_pairs();
    let exact = classify(Arithmetic::Exact, &pairs)?.verdicts;
    println!(
        "{path}: {} pairs, {} intersect (exact)",
        pairs.len(),
        exact.iter().filter(|v| **v).count()
    );
    println!(
        "{:<10} {:>6} {:>7} {:>7}",
        "arithmetic", "wrong", "false+", "false-"
    );
    for arithmetic in Arithmetic::all(&[8, 16, 24])? {
        let result = classify(arithmetic, &pairs)?;
        let false_positives = result
            .verdicts
            .iter()
            .zip(&exact)
            .filter(|(v, e)| **v && !**e)
            .count();
        let false_negatives = result
            .verdicts
            .iter()
            .zip(&exact)
            .filter(|(v, e)| !**v && **e)
            .count();
        let step = result
            .frame
            .map(|f| format!("  (grid step {:e})", f.step))
            .unwrap_or_default();
        println!(
            "{:<10} {:>6} {:>7} {:>7}{step}",
            arithmetic.to_string(),
            false_positives + false_negatives,
            false_positives,
            false_negatives
        );
    }
    if path == default {
        anyhow::ensure!(
            exact == SIX_PAIRS,
            "the exact answers {exact:?} are not the file's known answers {SIX_PAIRS:?}"
        );
        println!("the exact arithmetic gives the six known answers");
    }
    Ok(())
}
