//! glslViewer's `#include "file"` in the sandbox (docs/sandbox.md,
//! "Includes"): files found relative to the including file, errors at the
//! included file's own line, cycles, missing files, depth and size limits
//! as errors at the `#include`, and a change of an included file seen as a
//! change of the shader. Compiling only: no GPU needed.

mod common;

use std::path::{Path, PathBuf};

use raysandbox::sandbox::include::{MAX_BYTES, MAX_DEPTH};
use raysandbox::sandbox::{Session, Style, compile_file};

fn dir(name: &str) -> PathBuf {
    let dir = common::temp_dir("include", name);
    std::fs::create_dir_all(dir.join("lib")).unwrap();
    dir
}

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    common::write_file(dir, name, text)
}

const MAIN: &str = "\
uniform vec2 u_resolution;
#include \"lib/a.glsl\"
void main() {
    gl_FragColor = vec4(f(gl_FragCoord.xy / u_resolution), 1.0);
}
";

#[test]
fn an_error_in_an_included_file_is_at_its_own_line() {
    let dir = dir("error-line");
    write(
        &dir,
        "lib/a.glsl",
        "// a\n#include \"b.glsl\"\nvec3 f(vec2 p) { return g(p); }\n",
    );
    write(
        &dir,
        "lib/b.glsl",
        "// b\n\nvec3 g(vec2 p) {\n    return vec3(lenght(p));\n}\n",
    );
    let main = write(&dir, "main.frag", MAIN);
    let e = compile_file(&main).unwrap_err();
    assert!(e.file.ends_with("lib/b.glsl"), "{e}");
    assert_eq!((e.line, e.column), (4, 17), "{e}");
    assert_eq!(e.source_line, "    return vec3(lenght(p));", "{e}");
    assert!(e.message.contains("lenght"), "{e}");
    // The same file fixed: it compiles, in the glslViewer style, and the
    // includes are listed for the window to watch.
    write(
        &dir,
        "lib/b.glsl",
        "vec3 g(vec2 p) { return vec3(length(p)); }\n",
    );
    let compiled = compile_file(&main).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(compiled.style, Style::GlslViewer);
    let names: Vec<String> = compiled
        .includes
        .iter()
        .map(|p| p.strip_prefix(&dir).unwrap().display().to_string())
        .collect();
    assert_eq!(names, ["lib/a.glsl", "lib/b.glsl"]);
    // A parameter declared after the include has the line of its file.
    write(
        &dir,
        "main.frag",
        &MAIN.replace(
            "void main",
            "uniform float gain; // @slider(0, 1)\nvoid main",
        ),
    );
    let compiled = compile_file(&main).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(compiled.params.specs[0].line, 3);
    // An error in the including file after the include is at its own line.
    write(&dir, "main.frag", &MAIN.replace("vec4(f(", "vec4(ff("));
    let e = compile_file(&main).unwrap_err();
    assert_eq!(
        (e.file.as_str(), e.line),
        (main.to_str().unwrap(), 4),
        "{e}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn an_include_cycle_is_an_error_at_the_include_that_closes_it() {
    let dir = dir("cycle");
    write(
        &dir,
        "lib/a.glsl",
        "#include \"b.glsl\"\nvec3 f(vec2 p) { return vec3(p, 0.0); }\n",
    );
    write(&dir, "lib/b.glsl", "// b\n  #include \"a.glsl\"\n");
    let main = write(&dir, "main.frag", MAIN);
    let e = compile_file(&main).unwrap_err();
    assert!(e.file.ends_with("lib/b.glsl"), "{e}");
    assert_eq!((e.line, e.column), (2, 3), "{e}");
    assert!(
        e.message
            .contains("include cycle: \"a.glsl\" is already being included (a.glsl includes b.glsl includes a.glsl)"),
        "{e}"
    );
    // A file including itself.
    write(&dir, "lib/a.glsl", "#include \"a.glsl\"\n");
    let e = compile_file(&main).unwrap_err();
    assert!(e.file.ends_with("lib/a.glsl") && e.line == 1, "{e}");
    assert!(e.message.contains("include cycle"), "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_missing_include_is_an_error_at_its_line() {
    let dir = dir("missing");
    write(&dir, "lib/a.glsl", "\n\n#include \"gone.glsl\"\n");
    let main = write(&dir, "main.frag", MAIN);
    let e = compile_file(&main).unwrap_err();
    assert!(e.file.ends_with("lib/a.glsl") && e.line == 3, "{e}");
    assert!(e.message.starts_with("cannot read "), "{e}");
    assert!(e.message.contains("gone.glsl"), "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn includes_are_bounded_in_depth_and_size() {
    let dir = dir("bounds");
    // A chain one deeper than allowed: lib/n0.glsl includes n1.glsl, ...
    for k in 0..=MAX_DEPTH + 1 {
        write(
            &dir,
            &format!("lib/n{k}.glsl"),
            &format!("#include \"n{}.glsl\"\n", k + 1),
        );
    }
    write(&dir, "lib/a.glsl", "#include \"n0.glsl\"\n");
    let main = write(&dir, "main.frag", MAIN);
    let e = compile_file(&main).unwrap_err();
    assert!(
        e.message
            .contains(&format!("nested more than {MAX_DEPTH} deep")),
        "{e}"
    );
    // Files of 1 MB each, more of them than the limit allows.
    let big = format!("// {}\n", "x".repeat(1 << 20));
    let count = MAX_BYTES / big.len() + 1;
    let mut includes = String::new();
    for k in 0..count {
        write(&dir, &format!("lib/big{k}.glsl"), &big);
        includes.push_str(&format!("#include \"big{k}.glsl\"\n"));
    }
    write(&dir, "lib/a.glsl", &includes);
    let e = compile_file(&main).unwrap_err();
    assert!(
        e.file.ends_with("lib/a.glsl") && e.line == count as u32,
        "{e}"
    );
    assert!(e.message.contains("longer than 8 MB"), "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_change_of_an_included_file_is_a_change_of_the_shader() {
    let dir = dir("session");
    write(
        &dir,
        "lib/a.glsl",
        "vec3 f(vec2 p) { return vec3(p, 0.0); }\n",
    );
    let main = write(&dir, "main.frag", MAIN);
    let mut session = Session::new(&main);
    assert!(session.compile().unwrap().is_some());
    assert!(session.compile().unwrap().is_none(), "nothing changed");
    assert_eq!(session.includes(), [dir.join("lib/a.glsl")]);
    write(
        &dir,
        "lib/a.glsl",
        "vec3 f(vec2 p) { return vec3(p, 1.0) }\n",
    );
    let e = session.compile().unwrap_err();
    assert!(e.location().contains("lib/a.glsl:1:"), "{e}");
    // An include that went missing is an error, and the files read so far
    // are still watched.
    write(&dir, "lib/a.glsl", "#include \"later.glsl\"\n");
    let e = session.compile().unwrap_err();
    assert!(e.location().contains("lib/a.glsl:1:1"), "{e}");
    assert_eq!(session.includes(), [dir.join("lib/a.glsl")]);
    write(
        &dir,
        "lib/later.glsl",
        "vec3 f(vec2 p) { return vec3(p, 1.0); }\n",
    );
    assert!(session.compile().unwrap().is_some());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn an_include_without_a_file_on_disk_is_an_error_at_its_line() {
    let e =
        raysandbox::sandbox::compile("pasted.frag", "\n#include \"lib.glsl\"\nvoid main() {}\n")
            .unwrap_err();
    assert_eq!((e.line, e.column), (2, 1), "{e}");
    assert!(
        e.message.contains("needs the shader as a file on disk"),
        "{e}"
    );
}
