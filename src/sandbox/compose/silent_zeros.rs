//! No silent zeros (docs/sandbox.md, "Uniforms nobody sets"): a `uniform`
//! that no convention sets and that is not annotated as a parameter stays
//! 0, which in WebGL and here draws a black or flat picture without a word.
//! Each such uniform gives a warning, at its declaration, that the window,
//! the log, headless renders and `--check-all` report.

use std::fmt;

use super::glsl_decls::UniformDecl;
use crate::shader_params::parse_annotation;
use crate::shader_params::scan::Scan;

/// Something the user should know about a shader that compiled.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Warning {
    /// The file, as errors name it (an included file if it is there).
    pub file: String,
    /// 1-based line of the declaration.
    pub line: u32,
    pub message: String,
    pub kind: WarningKind,
}

/// What a [`Warning`] is about, for `--check-all`'s totals.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum WarningKind {
    /// A uniform nothing sets: it stays 0.
    SilentZero,
    /// A function that can end without a return: it returns 0 there.
    MissingReturn,
}

impl fmt::Display for Warning {
    /// `FILE:LINE: warning: MESSAGE`, as compilers write them.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}: warning: {}", self.file, self.line, self.message)
    }
}

/// A parameter no one sets: no annotation (no control asked for, no
/// `@default`) and no initializer.
pub(super) fn is_unset(scan: &Scan, decl: &UniformDecl) -> bool {
    if decl.initializer.is_some() {
        return false;
    }
    let comments = scan.comments_for_line(scan.line_of(decl.offset));
    // A wrong annotation is an error of its own, reported later.
    parse_annotation(&comments).is_ok_and(|a| a.control.is_none() && a.default.is_none())
}

/// The warning for `decl`, which stays 0; `control` says whether an
/// annotation could give it a control (a matrix cannot have one).
pub(super) fn warning(name: &str, scan: &Scan, decl: &UniformDecl, control: bool) -> Warning {
    let advice = if control {
        "annotate it to get a control (docs/sandbox.md, \"Parameters\")"
    } else {
        "a matrix gets no control: give it a value in the code"
    };
    Warning {
        file: name.to_string(),
        line: scan.line_of(decl.offset),
        message: format!(
            "uniform `{}` is not set by raysandbox: it stays 0; {advice}",
            decl.name
        ),
        kind: WarningKind::SilentZero,
    }
}
