//! The annotations of parameters: the `@tags` of the comments attached to a
//! declaration (docs/sandbox.md, "Parameters").

use super::Control;
use super::scan::{Comment, Scan};

/// What a comment says about a parameter.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Annotation {
    pub control: Option<Control>,
    /// `@default(...)`: numbers, `true`/`false`, or a `@select` label.
    pub default: Option<Vec<String>>,
    pub help: String,
}

/// An annotation error: byte offset in the scanned text and message.
pub type AnnotationError = (usize, String);

/// The annotation of a declaration on `line` (1-based) of `text`: the
/// `@tags` of the comments attached to it, read as the compiler reads them.
/// The tests and the fuzzer (docs/reliability.md) feed the parser through
/// it, with no shader to compile.
pub fn annotation_of_line(text: &str, line: u32) -> Result<Annotation, AnnotationError> {
    parse_annotation(&Scan::new(text).comments_for_line(line))
}

/// Reads the `@tags` of the comments attached to a declaration.
pub fn parse_annotation(comments: &[Comment]) -> Result<Annotation, AnnotationError> {
    let mut annotation = Annotation::default();
    let mut help = Vec::new();
    for comment in comments {
        let body = comment.body;
        let mut rest_start = 0;
        let mut text = String::new();
        let mut i = 0;
        while let Some(at) = body[i..].find('@').map(|n| i + n) {
            let name_end = at
                + 1
                + body[at + 1..]
                    .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
                    .unwrap_or(body.len() - at - 1);
            let name = &body[at + 1..name_end];
            if name.is_empty() {
                i = at + 1;
                continue;
            }
            let offset = comment.body_start + at;
            let after = body[name_end..].trim_start();
            let (args, end) = if after.starts_with('(') {
                let open = body.len() - after.len();
                let close = body[open..]
                    .find(')')
                    .map(|n| open + n)
                    .ok_or((offset, format!("@{name}: missing ')'")))?;
                let inner = &body[open + 1..close];
                let args: Vec<String> = if inner.trim().is_empty() {
                    Vec::new()
                } else {
                    inner.split(',').map(|a| a.trim().to_string()).collect()
                };
                (args, close + 1)
            } else {
                (Vec::new(), name_end)
            };
            text.push_str(&body[rest_start..at]);
            rest_start = end;
            i = end;
            let control = match name {
                "default" => {
                    if args.is_empty() {
                        return Err((offset, "@default needs a value: @default(1.5)".into()));
                    }
                    annotation.default = Some(args);
                    continue;
                }
                "slider" => {
                    let n = numbers(name, &args, 2..=3, offset)?;
                    if n[0] >= n[1] {
                        return Err((offset, format!("@slider: min {} >= max {}", n[0], n[1])));
                    }
                    if n.get(2).is_some_and(|s| *s <= 0.0) {
                        return Err((offset, "@slider: the step must be > 0".into()));
                    }
                    Control::Slider {
                        min: n[0],
                        max: n[1],
                        step: n.get(2).copied(),
                    }
                }
                "log" => {
                    let n = numbers(name, &args, 2..=2, offset)?;
                    if !(n[0] > 0.0 && n[0] < n[1]) {
                        return Err((offset, "@log(min, max) needs 0 < min < max".into()));
                    }
                    Control::Log {
                        min: n[0],
                        max: n[1],
                    }
                }
                "color" | "colour" => match args.as_slice() {
                    [] => Control::Color { linear: false },
                    [a] if a == "linear" => Control::Color { linear: true },
                    [a] if a == "srgb" => Control::Color { linear: false },
                    _ => {
                        return Err((
                            offset,
                            "@color takes no argument, or `linear` or `srgb`".into(),
                        ));
                    }
                },
                "checkbox" => {
                    if !args.is_empty() {
                        return Err((offset, "@checkbox takes no arguments".into()));
                    }
                    Control::Checkbox
                }
                "select" => {
                    if args.is_empty() || args.iter().any(String::is_empty) {
                        return Err((offset, "@select needs labels: @select(a, b, c)".into()));
                    }
                    Control::Select(
                        args.iter()
                            .map(|a| a.trim_matches('"').to_string())
                            .collect(),
                    )
                }
                "drag" => {
                    let n = numbers(name, &args, 0..=1, offset)?;
                    Control::Drag {
                        speed: n.first().copied(),
                    }
                }
                other => {
                    return Err((
                        offset,
                        format!(
                            "unknown annotation @{other}: use @slider(min, max, step), @log(min, max), \
                             @color, @checkbox, @select(a, b, ...), @drag(speed) or @default(value)"
                        ),
                    ));
                }
            };
            if annotation.control.is_some() {
                return Err((offset, format!("a second control annotation (@{name})")));
            }
            annotation.control = Some(control);
        }
        text.push_str(&body[rest_start..]);
        let text = text.trim().trim_start_matches(['-', ':']).trim();
        if !text.is_empty() {
            help.push(text.to_string());
        }
    }
    annotation.help = help.join(" ");
    Ok(annotation)
}

fn numbers(
    tag: &str,
    args: &[String],
    count: std::ops::RangeInclusive<usize>,
    offset: usize,
) -> Result<Vec<f64>, AnnotationError> {
    if !count.contains(&args.len()) {
        let expected = match tag {
            "slider" => "@slider(min, max) or @slider(min, max, step)",
            "log" => "@log(min, max)",
            _ => "@drag or @drag(speed)",
        };
        return Err((offset, format!("expected {expected}")));
    }
    args.iter()
        .map(|a| parse_number(a).ok_or((offset, format!("@{tag}: {a:?} is not a number"))))
        .collect()
}

/// A number as written in WGSL or GLSL: `1`, `-0.5`, `1e-4`, `2.0f`, `3u`.
pub fn parse_number(text: &str) -> Option<f64> {
    let t = text.trim();
    t.parse::<f64>()
        .ok()
        .or_else(|| {
            t.strip_suffix(['f', 'u', 'i', 'h', 'F', 'U'])
                .and_then(|s| s.parse().ok())
        })
        .filter(|v: &f64| v.is_finite())
}
