//! The report's files: one self-contained HTML page (inline SVG plots, each
//! beside its table), `report.json` and CSV tables. Every number on the
//! page comes from the [`Report`] that `report.json` serializes.

use super::{plots, Report};
use std::fmt::Write as _;
use std::path::Path;

/// A table: a header and rows of cells, as text.
struct Table {
    header: Vec<&'static str>,
    rows: Vec<Vec<String>>,
}

impl Table {
    fn csv(&self) -> String {
        let quote = |c: &str| {
            if c.contains([',', '"', '\n']) {
                format!("\"{}\"", c.replace('"', "\"\""))
            } else {
                c.to_string()
            }
        };
        let mut out = self
            .header
            .iter()
            .map(|h| quote(h))
            .collect::<Vec<_>>()
            .join(",")
            + "\n";
        for row in &self.rows {
            out += &(row.iter().map(|c| quote(c)).collect::<Vec<_>>().join(",") + "\n");
        }
        out
    }

    fn html(&self) -> String {
        let mut out = String::from("<table><thead><tr>");
        for h in &self.header {
            let _ = write!(out, "<th>{}</th>", escape(h));
        }
        out += "</tr></thead><tbody>";
        for row in &self.rows {
            out += "<tr>";
            for c in row {
                let _ = write!(out, "<td>{}</td>", escape(c));
            }
            out += "</tr>";
        }
        out + "</tbody></table>"
    }
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

fn opt<T: ToString>(v: Option<T>) -> String {
    v.map_or_else(|| "-".to_string(), |v| v.to_string())
}

fn fixed(v: Option<f64>, digits: usize) -> String {
    v.map_or_else(|| "-".to_string(), |v| format!("{v:.digits$}"))
}

fn sci(v: Option<f64>) -> String {
    v.map_or_else(|| "-".to_string(), |v| format!("{v:.3e}"))
}

/// Speed against error, one row per width.
fn widths_table(report: &Report) -> Table {
    let header = vec![
        "W",
        "wrong",
        "false+",
        "false-",
        "wrong %",
        "uncertain",
        "uncertain %",
        "re-check ns/pair",
        "LUT (xc7)",
        "FF (xc7)",
        "DSP48E1 (xc7)",
        "SRL (xc7)",
        "rare cases",
        "Fmax MHz (ECP5)",
        "LUT4 (ECP5)",
        "MULT18X18D (ECP5)",
        "P on ECP5-85",
        "pairs/s",
        "pairs/s per MULT18X18D",
        "Pareto",
    ];
    let rows = report
        .widths
        .iter()
        .map(|w| {
            let e = w.error.as_ref();
            vec![
                w.width.to_string(),
                opt(e.map(|e| e.wrong)),
                opt(e.map(|e| e.false_positives)),
                opt(e.map(|e| e.false_negatives)),
                fixed(w.wrong_rate().map(|r| 100.0 * r), 4),
                opt(e.and_then(|e| e.uncertain)),
                fixed(w.uncertain_rate().map(|r| 100.0 * r), 4),
                fixed(e.and_then(|e| e.recheck_ns_per_pair), 1),
                opt(w.xilinx.as_ref().map(|x| x.lut)),
                opt(w.xilinx.as_ref().map(|x| x.ff)),
                opt(w.xilinx.as_ref().map(|x| x.dsp48e1)),
                opt(w.xilinx.as_ref().map(|x| x.srl)),
                w.rare_cases.name().into(),
                fixed(w.ecp5.as_ref().map(|r| r.fmax_mhz), 1),
                opt(w.ecp5.as_ref().map(|r| r.lut4)),
                opt(w.ecp5.as_ref().map(|r| r.mult18x18d)),
                opt(w.ecp5_pipelines),
                sci(w.pairs_per_second),
                sci(w.pairs_per_second_per_multiplier),
                if w.pareto { "yes".into() } else { "-".into() },
            ]
        })
        .collect();
    Table { header, rows }
}

/// One pipeline's resources per width, both flows.
fn hardware_table(report: &Report) -> Table {
    let header = vec![
        "W",
        "rare cases",
        "LUT",
        "FF",
        "DSP48E1",
        "CARRY4",
        "SRL",
        "Fmax MHz",
        "LUT4",
        "FF (ECP5)",
        "MULT18X18D",
        "EBR",
    ];
    let rows = report
        .widths
        .iter()
        .map(|w| {
            let x = w.xilinx.as_ref();
            let e = w.ecp5.as_ref();
            vec![
                w.width.to_string(),
                w.rare_cases.name().into(),
                opt(x.map(|x| x.lut)),
                opt(x.map(|x| x.ff)),
                opt(x.map(|x| x.dsp48e1)),
                opt(x.map(|x| x.carry4)),
                opt(x.map(|x| x.srl)),
                fixed(e.map(|e| e.fmax_mhz), 1),
                opt(e.map(|e| e.lut4)),
                opt(e.map(|e| e.ff)),
                opt(e.map(|e| e.mult18x18d)),
                opt(e.map(|e| e.ebr)),
            ]
        })
        .collect();
    Table { header, rows }
}

/// `eval`'s rows, every arithmetic: the total alone, or every batch and
/// the total.
fn errors_table(report: &Report, every_batch: bool) -> Option<Table> {
    let errors = report.errors.as_ref()?;
    let batches: Vec<&crate::eval::BatchReport> = if every_batch {
        errors
            .batches
            .iter()
            .chain(std::iter::once(&errors.total))
            .collect()
    } else {
        vec![&errors.total]
    };
    let header = vec![
        "batch",
        "pairs",
        "arithmetic",
        "wrong",
        "false+",
        "false-",
        "ns/pair",
        "kernel ns/pair",
        "grid",
        "uncertain",
        "re-check ns/pair",
        "certified wrong",
        "step h",
    ];
    let mut rows = Vec::new();
    for batch in batches {
        for r in &batch.rows {
            rows.push(vec![
                batch.name.clone(),
                batch.pairs.to_string(),
                r.arithmetic.clone(),
                r.wrong.to_string(),
                r.false_positives.to_string(),
                r.false_negatives.to_string(),
                format!("{:.1}", r.ns_per_pair),
                fixed(r.kernel_ns_per_pair, 1),
                opt(r.grid_exact_disagreements),
                opt(r.uncertain),
                fixed(r.recheck_ns_per_pair, 1),
                opt(r.certified_wrong),
                r.step.map_or_else(|| "-".into(), |s| format!("{s:.3e}")),
            ]);
        }
    }
    Some(Table { header, rows })
}

/// The software baselines on the pair files' total.
fn baselines_table(report: &Report) -> Table {
    let header = vec![
        "arithmetic",
        "wrong",
        "false+",
        "false-",
        "ns/pair (one thread)",
        "pairs/s",
    ];
    let rows = report
        .baselines
        .iter()
        .map(|b| {
            vec![
                b.arithmetic.clone(),
                b.wrong.to_string(),
                b.false_positives.to_string(),
                b.false_negatives.to_string(),
                format!("{:.1}", b.ns_per_pair),
                format!("{:.3e}", 1e9 / b.ns_per_pair.max(f64::MIN_POSITIVE)),
            ]
        })
        .collect();
    Table { header, rows }
}

fn scene_table(report: &Report) -> Option<Table> {
    let scene = report.scene.as_ref()?;
    let header = vec![
        "W",
        "P",
        "pairs tested",
        "leaves",
        "cells",
        "narrow-phase cycles",
        "first in to last out cycles",
        "clock MHz",
        "clock",
        "rare cases",
        "stall cycles (bound)",
        "time ms",
        "x software",
        "intersecting (grid)",
        "uncertain",
        "missing",
        "extra",
        "certified missing",
        "certified extra",
    ];
    let rows = scene
        .rows
        .iter()
        .map(|r| {
            vec![
                r.width.to_string(),
                r.pipelines.to_string(),
                r.pairs_tested.to_string(),
                r.leaves.to_string(),
                r.cells.to_string(),
                r.cycles.to_string(),
                r.whole_cycles.to_string(),
                format!("{:.1}", r.clock_mhz),
                r.clock.name().into(),
                r.rare_cases.name().into(),
                r.stall_cycles.to_string(),
                format!("{:.4}", 1e3 * r.whole_seconds),
                r.speedup
                    .map_or_else(|| "-".to_string(), |x| format!("{x:.1}")),
                r.intersecting.to_string(),
                r.uncertain.to_string(),
                r.missing.to_string(),
                r.extra.to_string(),
                r.certified_missing.to_string(),
                r.certified_extra.to_string(),
            ]
        })
        .collect();
    Some(Table { header, rows })
}

const STYLE: &str = "body{font-family:sans-serif;margin:24px;max-width:1400px;color:#222}\
h1{font-size:22px}h2{font-size:18px;margin-top:32px;border-bottom:1px solid #ccc}\
.pair{display:flex;flex-wrap:wrap;gap:24px;align-items:flex-start}\
table{border-collapse:collapse;font-size:12px}td,th{border:1px solid #bbb;padding:3px 6px;text-align:right}\
th{background:#eee}td:first-child,th:first-child{text-align:left}p.note{font-size:13px;color:#444;max-width:1100px}";

/// Writes `report.html`, `report.json` and the CSV tables into `dir`.
pub fn write_all(dir: &Path, report: &Report) -> anyhow::Result<()> {
    std::fs::create_dir_all(dir).map_err(|e| anyhow::anyhow!("--out {}: {e}", dir.display()))?;
    let widths = widths_table(report);
    let errors = errors_table(report, true);
    let total = errors_table(report, false);
    let baselines = baselines_table(report);
    let scene = scene_table(report);
    let write = |name: &str, text: &str| -> anyhow::Result<()> {
        let path = dir.join(name);
        std::fs::write(&path, text).map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))
    };
    write(
        "report.json",
        &(serde_json::to_string_pretty(report)? + "\n"),
    )?;
    write("widths.csv", &widths.csv())?;
    if let Some(t) = &errors {
        write("errors.csv", &t.csv())?;
    }
    if let Some(t) = &scene {
        write("scene.csv", &t.csv())?;
    }

    let mut html = format!(
        "<!DOCTYPE html><html><head><meta charset=\"utf-8\"><title>tritri: speed against error</title><style>{STYLE}</style></head><body>\
         <h1>tritri: speed against error</h1><p class=\"note\"><code>{}</code><br>Hardware figures: {} (measured {}); \
         hardware speed is one pair per clock per pipeline, \
         with P = {} pipelines or as many as fit the {}'s {} multipliers, \
         at the ECP5 post-route clock of the system of those pipelines where it was routed, else of the pipeline alone. \
         A width's pipeline is the one routed: its rare pairs on parallel units, \
         or on the shared unit where only that one was routed (\"rare cases\"), \
         whose stalls the scene's time counts by the stall model's bound.</p>",
        escape(&report.command),
        escape(&report.measurements),
        escape(&report.measured),
        report.pipelines,
        super::ecp5_device().part,
        super::ecp5_device().dsps
    );
    let section = |html: &mut String,
                   title: &str,
                   plot: Option<String>,
                   table: Option<&Table>,
                   note: &str| {
        let table = table.filter(|t| !t.rows.is_empty());
        if plot.is_none() && table.is_none() {
            return;
        }
        let _ = write!(
            html,
            "<h2>{}</h2><p class=\"note\">{}</p><div class=\"pair\">",
            escape(title),
            note
        );
        if let Some(svg) = plot {
            let _ = write!(html, "<div>{svg}</div>");
        }
        if let Some(t) = table {
            let _ = write!(html, "<div>{}</div>", t.html());
        }
        html.push_str("</div>");
    };
    let inputs = report
        .errors
        .as_ref()
        .map_or_else(|| "no pair files".to_string(), |e| e.inputs.join(", "));
    section(
        &mut html,
        "Speed against error, per width",
        None,
        Some(&widths),
        &format!(
            "Errors on {} ({} pairs): a wrong verdict is a grid verdict that differs from the exact one on the original coordinates. \
             Uncertain verdicts carry no certificate (<code>out_certain = 0</code>); the host decides them again, which makes every answer exact. \
             A dash: not measured (no pair files, or no post-route run at that width).",
            escape(&inputs),
            report.errors.as_ref().map_or(0, |e| e.total.pairs)
        ),
    );
    section(
        &mut html,
        "Error against W",
        plots::errors(report)?,
        total.as_ref(),
        "Every arithmetic on all the pairs, as <code>tritri eval</code> prints it (every batch below).",
    );
    if let Some(t) = &errors {
        let _ = write!(
            html,
            "<details><summary>every batch</summary>{}</details>",
            t.html()
        );
    }
    section(&mut html, "Hardware cost against W", plots::cost(report)?, Some(&hardware_table(report)), "One pipeline: Yosys <code>synth_xilinx</code> for a 7-series part, and nextpnr-ecp5 post-route on an LFE5U-85F (speed 6) where routed.");
    section(&mut html, "Speed against W", plots::speed(report)?, Some(&baselines), "The software baselines, timed on this machine in this run (one thread; the fastest of repeated samples).");
    section(
        &mut html,
        "Throughput per multiplier against error",
        plots::pareto(report)?,
        None,
        "Only widths with a post-route clock have a throughput; red points are on the Pareto front (no other width is both as right and as fast per multiplier).",
    );
    if let (Some(s), Some(t)) = (&report.scene, &scene) {
        let note = format!(
            "A = {} ({} triangles), B = {} ({} triangles), pose of B {}: {} intersecting pairs (exact f64 on the originals), software {:.3} ms. \
             The model engine of <code>tritri sim</code> with the octree broad phase; time from the first triangle in to the last pair out.",
            escape(&s.a),
            s.triangles_a,
            escape(&s.b),
            s.triangles_b,
            escape(&s.pose_b),
            s.exact_pairs,
            1e3 * s.software_seconds
        );
        section(
            &mut html,
            "Scene",
            Some(plots::scene(s, &report.widths)?),
            Some(t),
            &note,
        );
        section(
            &mut html,
            "Scene: error against W",
            Some(plots::scene_errors(s, &report.widths)?),
            None,
            "With certificates the answer is exact at every width (the green line stays at the floor); what a narrower grid costs is the host's re-checks.",
        );
    }
    html.push_str("</body></html>\n");
    write("report.html", &html)
}
