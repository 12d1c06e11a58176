//! The stress table: console lines, CSV and Markdown, and the summary of
//! the series (largest distance, translation and scale that still pass).

use std::fmt::Write;

use super::Invariance;
use super::metrics::{Comparison, MAX_FLIP, MAX_ID_MISMATCH};
use super::scenes::{SERIES, series_member};

/// One scene's results.
pub struct Row {
    pub name: String,
    pub group: &'static str,
    pub robust: Comparison,
    pub naive: Comparison,
}

fn pass(c: &Comparison) -> &'static str {
    if c.passes() { "pass" } else { "FAIL" }
}

fn psnr(c: &Comparison) -> String {
    if c.psnr.is_finite() {
        format!("{:.1}", c.psnr)
    } else {
        "inf".to_string()
    }
}

pub fn console_header() -> String {
    format!(
        "{:<26} | {:>7} {:>7} {:>7} {:>5} {:>6} {:>4} | {:>7} {:>7} {:>7} {:>5} {:>6} {:>4}",
        "scene (robust | naive)",
        "FLIP",
        "id %",
        ">8 %",
        "PSNR",
        "acne %",
        "",
        "FLIP",
        "id %",
        ">8 %",
        "PSNR",
        "acne %",
        ""
    )
}

fn console_cells(c: &Comparison) -> String {
    let nan = if c.nan_pixels > 0 {
        format!(" NaN {}", c.nan_pixels)
    } else {
        String::new()
    };
    format!(
        "{:>7.4} {:>7.3} {:>7.3} {:>5} {:>6.3} {:>4}{nan}",
        c.flip_mean,
        c.id_mismatch * 100.0,
        c.frac_over_8 * 100.0,
        psnr(c),
        c.false_shadow * 100.0,
        pass(c)
    )
}

pub fn console_row(row: &Row) -> String {
    format!(
        "{:<26} | {} | {}",
        row.name,
        console_cells(&row.robust),
        console_cells(&row.naive)
    )
}

pub fn csv(rows: &[Row]) -> String {
    let mut out = String::from(
        "scene,group,variant,rmse,psnr_db,flip_mean,frac_over_8,id_mismatch,nan_pixels,false_shadow,lit_pixels,pass\n",
    );
    for row in rows {
        for (variant, c) in [("robust", &row.robust), ("naive", &row.naive)] {
            writeln!(
                out,
                "{},{},{variant},{:.6},{:.3},{:.6},{:.6},{:.6},{},{:.6},{},{}",
                row.name,
                row.group,
                c.rmse,
                c.psnr,
                c.flip_mean,
                c.frac_over_8,
                c.id_mismatch,
                c.nan_pixels,
                c.false_shadow,
                c.lit_pixels,
                c.passes()
            )
            .unwrap();
        }
    }
    out
}

/// `D = 10^k`, `x 10^k`: how the exponent of a series reads.
fn power(k: i32) -> String {
    format!("1e{k}")
}

/// Per series, for robust and naive: the range of k (starting at the first
/// member and going up, or for `scale` going out from 10^0 both ways) over
/// which every member passes (`scale`, `scaled`: from 10^0 both ways).
pub fn series_summary(rows: &[Row]) -> String {
    let mut out = String::from("| series | robust passes | naive passes |\n| --- | --- | --- |\n");
    for (series, meaning) in SERIES {
        let mut members: Vec<(i32, &Row)> = rows
            .iter()
            .filter_map(|r| {
                let (s, k) = series_member(&r.name)?;
                (s == *series).then_some((k, r))
            })
            .collect();
        if members.is_empty() {
            continue;
        }
        members.sort_by_key(|(k, _)| *k);
        let cell = |variant: fn(&Row) -> &Comparison| -> String {
            let passes = |k: i32| {
                members
                    .iter()
                    .find(|(kk, _)| *kk == k)
                    .is_some_and(|(_, r)| variant(r).passes())
            };
            let ks: Vec<i32> = members.iter().map(|(k, _)| *k).collect();
            if series.starts_with("scale") {
                if !passes(0) {
                    return "fails at 1e0".to_string();
                }
                let hi = ks
                    .iter()
                    .filter(|&&k| k >= 0)
                    .take_while(|&&k| passes(k))
                    .last();
                let lo = ks
                    .iter()
                    .rev()
                    .filter(|&&k| k <= 0)
                    .take_while(|&&k| passes(k))
                    .last();
                return format!(
                    "{} .. {}",
                    power(*lo.unwrap_or(&0)),
                    power(*hi.unwrap_or(&0))
                );
            }
            let good: Vec<i32> = ks.iter().copied().take_while(|&k| passes(k)).collect();
            match (good.last(), ks.get(good.len())) {
                (None, _) => format!("none (fails at {})", power(ks[0])),
                (Some(&k), None) => format!("up to {} (all)", power(k)),
                (Some(&k), Some(&next)) => format!("up to {} (fails at {})", power(k), power(next)),
            }
        };
        writeln!(
            out,
            "| `{series}`: {meaning} | {} | {} |",
            cell(|r| &r.robust),
            cell(|r| &r.naive)
        )
        .unwrap();
    }
    out
}

fn md_cells(c: &Comparison) -> String {
    let nan = if c.nan_pixels > 0 {
        format!(" ({} NaN)", c.nan_pixels)
    } else {
        String::new()
    };
    format!(
        "{:.4} | {:.3} | {:.2} | {:.4} | {} | {:.3} | {}{nan}",
        c.flip_mean,
        c.id_mismatch * 100.0,
        c.frac_over_8 * 100.0,
        c.rmse,
        psnr(c),
        c.false_shadow * 100.0,
        if c.passes() { "pass" } else { "**FAIL**" }
    )
}

/// The table of every scene, robust and naive side by side.
pub fn markdown_table(rows: &[Row]) -> String {
    let mut out = String::from(
        "| scene | FLIP | id % | >8 % | RMSE | PSNR | acne % | | FLIP | id % | >8 % | RMSE | PSNR | acne % | |\n\
         | --- | ---: | ---: | ---: | ---: | ---: | ---: | --- | ---: | ---: | ---: | ---: | ---: | ---: | --- |\n",
    );
    for row in rows {
        let name = if row.group == "bundled" {
            format!("{} (bundled)", row.name)
        } else {
            row.name.clone()
        };
        writeln!(
            out,
            "| {name} | {} | {} |",
            md_cells(&row.robust),
            md_cells(&row.naive)
        )
        .unwrap();
    }
    out
}

pub fn invariance_markdown(rows: &[Invariance]) -> String {
    let mut out = String::from(
        "| scene | scaled by | FLIP robust | FLIP naive | acne % robust | acne % naive |\n| --- | --- | ---: | ---: | ---: | ---: |\n",
    );
    for r in rows {
        writeln!(
            out,
            "| {} | {} | {:.4} | {:.4} | {:.3} | {:.3} |",
            r.name,
            power(r.factor_power),
            r.robust_flip,
            r.naive_flip,
            r.robust_false_shadow * 100.0,
            r.naive_false_shadow * 100.0
        )
        .unwrap();
    }
    out
}

pub fn markdown(
    rows: &[Row],
    summary: &str,
    invariance: &[Invariance],
    width: u32,
    height: u32,
) -> String {
    let mut out = String::new();
    writeln!(
        out,
        "# Stress table\n\n{width}x{height} pixels, 1 sample per pixel. Left: the robust shader \
         (`ROBUST = true`), right: the naive one, each against the f64 reference fed the same \
         f32-rounded scene. A render passes with FLIP mean <= {MAX_FLIP}, first-hit mismatch \
         <= {} % outside the one-pixel silhouette band, and no NaN pixel. \"acne %\" is the \
         fraction of lit pixels shown in shadow.\n",
        MAX_ID_MISMATCH * 100.0
    )
    .unwrap();
    out.push_str(&markdown_table(rows));
    out.push_str("\n## Series\n\n");
    out.push_str(summary);
    if !invariance.is_empty() {
        out.push_str("\n## Scale invariance\n\nFLIP of the render of the scaled scene against the render of the original, same variant.\n\n");
        out.push_str(&invariance_markdown(invariance));
    }
    out
}

/// The watertightness section of the report.
pub fn leaks_markdown(rows: &[super::leaks::LeakRow]) -> String {
    format!(
        "\n## Watertightness\n\nRays aimed exactly (in f64) at shared edges and vertices, from \
         in front of every triangle that meets there; a ray that meets none of those triangles \
         leaked. The GPU gets the same rays rounded to f32.\n\n{}",
        super::leaks::markdown(rows)
    )
}
