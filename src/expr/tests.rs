use glam::DVec3;

use super::*;

fn error_of(source: &str) -> ExprError {
    Function::parse(source).expect_err(source)
}

fn at(source: &str, x: f64, y: f64, z: f64) -> f64 {
    Function::parse(source)
        .unwrap_or_else(|e| panic!("{source}: {e}"))
        .value(DVec3::new(x, y, z))
}

#[test]
fn unknown_function_is_named_at_its_column() {
    let e = error_of("x + foo(y)");
    assert_eq!(e.column, 5, "{e}");
    assert!(e.message.contains("unknown function `foo`"), "{e}");
    assert!(e.message.contains("atan2"), "lists the known ones: {e}");
}

#[test]
fn unbalanced_parentheses_point_at_the_lonely_one() {
    let e = error_of("(x + 1");
    assert_eq!(e.column, 1, "{e}");
    assert!(e.message.contains("never closed"), "{e}");
    let e = error_of("sin(x * (y + 1)");
    assert_eq!(e.column, 4, "the call's `(`: {e}");
    let e = error_of("x + 1)");
    assert_eq!(e.column, 6, "{e}");
    assert!(e.message.contains("has no `(`"), "{e}");
}

#[test]
fn other_mistakes_name_their_column() {
    let cases = [
        ("", 1, "empty"),
        ("x +", 4, "found the end"),
        ("2x", 2, "expected an operator"),
        ("x + w", 5, "unknown name `w`"),
        ("sin + 1", 1, "is a function"),
        ("atan2(x)", 1, "takes 2 arguments, got 1"),
        ("sin(x, y)", 1, "takes 1 argument, got 2"),
        ("x # 2", 3, "unexpected character `#`"),
        ("x + exp(1000)", 5, "cannot hold"),
        ("y * (1 / 0)", 8, "cannot hold"),
        ("sqrt(-1) + x", 1, "NaN"),
        ("x + 1e39", 5, "cannot hold"),
        ("1..2", 1, "not a number"),
        ("min(x y)", 7, "expected `)`"),
    ];
    for (source, column, words) in cases {
        let e = error_of(source);
        assert_eq!(e.column, column, "{source:?}: {e}");
        assert!(e.message.contains(words), "{source:?}: {e}");
    }
}

#[test]
fn columns_count_characters_not_bytes() {
    let e = error_of("x·y");
    assert_eq!(e.column, 2, "{e}");
}

#[test]
fn deep_nesting_is_an_error_not_a_crash() {
    let source = format!("{}x{}", "(".repeat(10_000), ")".repeat(10_000));
    assert!(error_of(&source).message.contains("nested"));
    let source = format!("{}x", "-".repeat(10_000));
    assert!(error_of(&source).message.contains("nested"));
}

#[test]
fn precedence_is_the_usual_one() {
    assert_eq!(at("-x^2", 2.0, 0.0, 0.0), -4.0);
    assert_eq!(at("2^3^2", 0.0, 0.0, 0.0), 512.0);
    assert_eq!(at("1 + 2 * 3 - 4 / 2", 0.0, 0.0, 0.0), 5.0);
    assert_eq!(at("2 * -x", 3.0, 0.0, 0.0), -6.0);
    assert_eq!(at("x - y - z", 1.0, 2.0, 3.0), -4.0);
    assert_eq!(at("x^-2", 2.0, 0.0, 0.0), 0.25);
    assert_eq!(at("1.5e1 + .5", 0.0, 0.0, 0.0), 15.5);
}

#[test]
fn powers_whole_and_real() {
    assert_eq!(at("x^3", -2.0, 0.0, 0.0), -8.0);
    assert_eq!(at("x^3.0", -2.0, 0.0, 0.0), -8.0, "a whole real is whole");
    assert_eq!(at("pow(x, 2)", -3.0, 0.0, 0.0), 9.0);
    assert_eq!(at("x^0", 0.0, 0.0, 0.0), 1.0);
    assert!((at("x^0.5", 4.0, 0.0, 0.0) - 2.0).abs() < 1e-15);
    assert_eq!(
        at("x^0.5", -4.0, 0.0, 0.0),
        0.0,
        "the real power is 0 for x <= 0"
    );
    assert!((at("x^y", 2.0, 10.0, 0.0) - 1024.0).abs() < 1e-12);
}

#[test]
fn the_functions_written_with_others() {
    assert_eq!(at("fract(x)", -0.25, 0.0, 0.0), 0.75);
    assert_eq!(at("mod(x, 3)", -1.0, 0.0, 0.0), 2.0);
    assert_eq!(at("mod(x, -3)", 1.0, 0.0, 0.0), -2.0);
    assert_eq!(at("clamp(x, -1, 1)", 5.0, 0.0, 0.0), 1.0);
    assert_eq!(at("clamp(x, -1, 1)", -5.0, 0.0, 0.0), -1.0);
    assert_eq!(at("mix(x, y, 0.25)", 4.0, 8.0, 0.0), 5.0);
    assert_eq!(at("min(x, y) + max(x, z)", 1.0, 2.0, 3.0), 4.0);
    assert!((at("atan2(y, x)", -1.0, 0.0, 0.0) - std::f64::consts::PI).abs() < 1e-15);
    assert!((at("cos(pi)", 0.0, 0.0, 0.0) + 1.0).abs() < 1e-15);
}

#[test]
fn constants_are_folded() {
    let f = Function::parse("x * (2 + 3) + sin(pi / 2)").unwrap();
    let text = f.to_wgsl("f");
    let code: Vec<&str> = text.lines().filter(|l| !l.starts_with("//")).collect();
    let code = code.join("\n");
    assert!(code.contains("5.0f") && code.contains("1.0f"), "{text}");
    assert!(!code.contains("sin(") && !code.contains("pi"), "{text}");
}

#[test]
fn gradients_are_exact() {
    let f = Function::parse("x^3 + x * y - sin(z)").unwrap();
    let (v, g) = f.value_and_gradient(DVec3::new(2.0, 5.0, 0.0));
    assert_eq!(v, 18.0);
    assert_eq!(g, DVec3::new(12.0 + 5.0, 2.0, -1.0));
    let sphere = Function::parse("x^2 + y^2 + z^2 - 1").unwrap();
    let p = DVec3::new(0.3, -0.4, 0.5);
    assert_eq!(sphere.value_and_gradient(p).1, 2.0 * p);
    // Where the real power is the constant 0, so is its gradient.
    let root = Function::parse("x^0.5").unwrap();
    assert_eq!(
        root.value_and_gradient(DVec3::new(-1.0, 0.0, 0.0)).1,
        DVec3::ZERO
    );
    // abs has the derivative 0 at 0, as WGSL's sign.
    let abs = Function::parse("abs(x)").unwrap();
    assert_eq!(abs.value_and_gradient(DVec3::ZERO).1, DVec3::ZERO);
}

#[test]
fn generated_wgsl_validates_for_every_function() {
    let sources = [
        "sin(x) + cos(y) + tan(z) + asin(x / 4) + acos(y / 4) + atan(z)",
        "atan2(y, x) + sinh(x) + cosh(y) + tanh(z) + exp(x) + log(y * y + 1)",
        "sqrt(x * x + 1) + abs(y) + min(x, y) + max(y, z) + pow(x * x + 1, y)",
        "floor(x) + fract(y) + mod(z, 2) + clamp(x, -1, 1) + mix(x, y, z)",
        "x^7 + y^-3 + z^0.5 + x^y + 2^x - -z + pi",
        // Constant bases of powers that are not positive, or not as f32
        // (found by the fuzzer, docs/reliability.md): `log` of them was a
        // constant expression naga refuses.
        "0^x + (-2)^y + 1e-300^z + 1e-40^x + 3.4e38^y",
        "atan(-(--log(1e-400 ^ (y / ((x))))))",
        "atan2(x, -1e38) + atan2(1e30, y)",
        "1.5",
    ];
    for (i, source) in sources.iter().enumerate() {
        let f = Function::parse(source).unwrap();
        let text = f.to_wgsl(&format!("f{i}"));
        let module = naga::front::wgsl::parse_str(&text)
            .unwrap_or_else(|e| panic!("{}\n{text}", e.emit_to_string(&text)));
        naga::valid::Validator::new(
            naga::valid::ValidationFlags::all(),
            naga::valid::Capabilities::default(),
        )
        .validate(&module)
        .unwrap_or_else(|e| panic!("{source}: {e:?}\n{text}"));
    }
}
