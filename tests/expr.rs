//! User functions of implicit surfaces (`raysandbox::expr`): the dual-number
//! gradient against finite differences, and the generated WGSL, run on the
//! GPU (lavapipe where there is no GPU), against the f64 evaluation, on
//! random functions of the whole syntax.

mod common;
#[path = "expr/error_model.rs"]
mod error_model;

use glam::DVec3;
use proptest::prelude::*;
use proptest::test_runner::{Config, TestRunner};
use raysandbox::expr::Function;
use raysandbox::gpu::{Gpu, ShaderSource};

/// A number of the form n / 8, small and exact in f32.
fn number() -> impl Strategy<Value = String> {
    (-16i32..=16).prop_map(|n| format!("{}", f64::from(n) / 8.0))
}

fn leaf() -> BoxedStrategy<String> {
    prop_oneof![
        Just("x".to_string()),
        Just("y".to_string()),
        Just("z".to_string()),
        number(),
    ]
    .boxed()
}

/// Random functions built from every operation of the syntax, each kept
/// inside its domain and away from overflow (`sqrt(a^2 + 0.5)`, not
/// `sqrt(a)`), so that a difference between two evaluations means a
/// different rule and not a different rounding of a singularity. `smooth`
/// leaves out the functions with kinks (`abs`, `min`, `max`, `clamp`), where
/// a finite difference straddling the kink is wrong.
fn function(smooth: bool) -> impl Strategy<Value = String> {
    leaf().prop_recursive(4, 24, 2, move |inner| {
        let pair = (inner.clone(), inner.clone());
        let smooth_ops = prop_oneof![
            pair.clone().prop_map(|(a, b)| format!("({a} + {b})")),
            pair.clone().prop_map(|(a, b)| format!("({a} - {b})")),
            pair.clone().prop_map(|(a, b)| format!("({a} * {b})")),
            pair.clone()
                .prop_map(|(a, b)| format!("({a} / (({b})^2 + 1))")),
            inner.clone().prop_map(|a| format!("(-{a})")),
            inner.clone().prop_map(|a| format!("sin({a})")),
            inner.clone().prop_map(|a| format!("cos({a})")),
            inner.clone().prop_map(|a| format!("tan(0.5 * sin({a}))")),
            inner.clone().prop_map(|a| format!("asin(0.9 * sin({a}))")),
            inner.clone().prop_map(|a| format!("acos(0.9 * cos({a}))")),
            inner.clone().prop_map(|a| format!("atan({a})")),
            pair.clone()
                .prop_map(|(a, b)| format!("atan2({a}, ({b})^2 + 0.5)")),
            inner.clone().prop_map(|a| format!("sinh(sin({a}))")),
            inner.clone().prop_map(|a| format!("cosh(cos({a}))")),
            inner.clone().prop_map(|a| format!("tanh({a})")),
            inner.clone().prop_map(|a| format!("exp(sin({a}))")),
            inner.clone().prop_map(|a| format!("log(({a})^2 + 0.5)")),
            inner.clone().prop_map(|a| format!("sqrt(({a})^2 + 0.5)")),
            pair.clone()
                .prop_map(|(a, b)| format!("pow(({a})^2 + 0.5, sin({b}))")),
            inner.clone().prop_map(|a| format!("({a})^3")),
            inner.clone().prop_map(|a| format!("(({a})^2 + 0.5)^-2")),
            inner.clone().prop_map(|a| format!("(({a})^2 + 0.5)^0.5")),
            (inner.clone(), inner.clone(), inner.clone())
                .prop_map(|(a, b, t)| format!("mix({a}, {b}, sin({t}))")),
        ];
        if smooth {
            smooth_ops.boxed()
        } else {
            prop_oneof![
                4 => smooth_ops,
                1 => inner.clone().prop_map(|a| format!("abs({a})")),
                1 => pair.clone().prop_map(|(a, b)| format!("min({a}, {b})")),
                1 => pair.clone().prop_map(|(a, b)| format!("max({a}, {b})")),
                1 => inner.clone().prop_map(|a| format!("clamp({a}, -1, 1)")),
            ]
            .boxed()
        }
    })
}

fn point() -> impl Strategy<Value = DVec3> {
    [-1.5f64..1.5, -1.5f64..1.5, -1.5f64..1.5].prop_map(DVec3::from_array)
}

/// The central difference along each axis with step `h`.
fn central_difference(f: &Function, p: DVec3, h: f64) -> DVec3 {
    DVec3::from_array(
        [DVec3::X, DVec3::Y, DVec3::Z]
            .map(|e| (f.value(p + h * e) - f.value(p - h * e)) / (2.0 * h)),
    )
}

proptest! {
    #![proptest_config(Config::with_cases(512))]

    /// The dual-number gradient is the derivative: a finite difference
    /// agrees with it to within its own error, estimated from the
    /// difference of two step sizes (Richardson), plus rounding.
    #[test]
    fn gradient_matches_finite_differences(source in function(true), p in point()) {
        let f = Function::parse(&source).unwrap_or_else(|e| panic!("{source}: {e}"));
        let (value, gradient) = f.value_and_gradient(p);
        let h = 1e-4;
        let coarse = central_difference(&f, p, h);
        let fine = central_difference(&f, p, h / 2.0);
        for axis in 0..3 {
            let truncation = (coarse[axis] - fine[axis]).abs();
            let rounding = 1e-15 * (1.0 + value.abs()) / h;
            let tolerance = 2.0 * truncation + 100.0 * rounding + 1e-9 * gradient[axis].abs();
            let error = (fine[axis] - gradient[axis]).abs();
            prop_assert!(
                error <= tolerance,
                "{source} at {p}: axis {axis}: dual {} vs finite difference {} (error {error:e}, tolerance {tolerance:e})",
                gradient[axis], fine[axis]
            );
        }
    }
}

/// What the GPU computed for one function at one point.
#[derive(Debug, Clone, Copy)]
struct GpuValue {
    value: f32,
    dual: [f32; 4],
}

/// Runs `functions` on the GPU: `points[i]` (xyz, and in w the index of the
/// function) through `user_f{w}` and `user_f{w}_dual`, the generated WGSL as the
/// shader gets it.
fn run_on_gpu(gpu: &Gpu, functions: &[Function], points: &[[f32; 4]]) -> Vec<GpuValue> {
    let mut wgsl = String::new();
    let mut cases = String::new();
    for (i, f) in functions.iter().enumerate() {
        wgsl.push_str(&f.to_wgsl(&format!("user_f{i}")));
        cases.push_str(&format!(
            "        case {i}u: {{ value = user_f{i}(p); dual = user_f{i}_dual(p); }}\n"
        ));
    }
    let harness = format!(
        "// A pipeline constant, as the tracer has: wgpu then runs naga's\n\
         // override processing over the functions too.\n\
         override ENABLED: bool = false;\n\
         @group(0) @binding(0) var<storage, read> points: array<vec4<f32>>;\n\
         @group(0) @binding(1) var<storage, read_write> results: array<vec4<f32>>;\n\
         @compute @workgroup_size(64)\n\
         fn run(@builtin(global_invocation_id) id: vec3<u32>) {{\n\
         let i = id.x;\n\
         if i >= arrayLength(&points) || !ENABLED {{ return; }}\n\
         let p = points[i].xyz;\n\
         var value = 0.0f;\n\
         var dual = vec4<f32>(0.0f);\n\
         switch u32(points[i].w) {{\n{cases}        default: {{}}\n    }}\n\
         results[2u * i] = vec4<f32>(value, 0.0f, 0.0f, 0.0f);\n\
         results[2u * i + 1u] = dual;\n}}\n"
    );
    let source = ShaderSource::from_parts([
        ("functions.wgsl".to_string(), wgsl),
        ("harness.wgsl".to_string(), harness),
    ]);
    let kernel = raysandbox::gpu::compute::Kernel {
        label: "expression harness",
        source: &source,
        entry: "run",
        constants: &[("ENABLED", 1.0)],
        group: 0,
    };
    let vectors: Vec<[f32; 4]> = kernel.run(gpu, points, points.len() * 2);
    vectors
        .chunks(2)
        .map(|pair| GpuValue {
            value: pair[0][0],
            dual: pair[1],
        })
        .collect()
}

/// How far an f32 evaluation may be from the f64 one: a part relative to
/// the value; a multiple of what f32 arithmetic itself loses on this
/// function at this point (the CPU's f32 evaluation against its f64 one: a
/// large loss means an ill-conditioned function, where the GPU's own
/// roundings are amplified the same way); and a multiple of how far the
/// errors WGSL allows each operation move the exact result
/// ([`error_model::deviation`]), which sees what the CPU's accurate f32
/// functions cannot: the GPU's `asin` 4096 ulps off inside a cancellation.
struct Tolerance {
    value: f64,
    gradient: DVec3,
}

/// The relative part. On lavapipe the largest error seen over these tests
/// outside ill-conditioned points was 4e-4 of `1 + |value|`, a fifth of
/// this; a wrong rule is off by far more (changing one derivative's sign
/// fails at once).
const RELATIVE: f64 = 2e-3;

/// The error model's sign patterns sample its worst case; this margin covers
/// the patterns not tried.
const MODEL_MARGIN: f64 = 4.0;

impl Tolerance {
    fn at(f: &Function, p: DVec3, value: f64, gradient: DVec3, value32: f64) -> Tolerance {
        let (value_deviation, gradient_deviation) = error_model::deviation(f, p);
        let loss = (value32 - value).abs();
        let relative_loss = loss / (1.0 + value.abs());
        Tolerance {
            value: RELATIVE * (1.0 + value.abs()) + 64.0 * loss + MODEL_MARGIN * value_deviation,
            gradient: DVec3::splat((RELATIVE + 64.0 * relative_loss) * (1.0 + gradient.length()))
                + MODEL_MARGIN * gradient_deviation,
        }
    }
}

/// The f64 gradients the GPU's may be: at p, and at the points h away from
/// it along each axis. Within f32's error of a kink (a tie of `min` or
/// `max`, `abs` at 0) the f32 evaluation may take the other branch, and its
/// gradient is then a neighbour's: h = 2e-3 (1 + |p|) reaches ties as far
/// as the GPU's own errors move them (a random function once put a tie of
/// `max` 4e-4 from a random point), and is small enough that a neighbour on
/// the same branch differs from p by less than the tolerance.
fn gradients_near(f: &Function, p: DVec3) -> Vec<DVec3> {
    let h = 2e-3 * (1.0 + p.abs().max_element());
    let steps = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z];
    steps
        .into_iter()
        .flat_map(|e| [p + h * e, p - h * e])
        .skip(1)
        .map(|q| f.value_and_gradient(q).1)
        .collect()
}

/// Compares the GPU with the CPU for `functions` at `points` (each point
/// with every function); a message per mismatch. The value must match the
/// f64 value at the point, the gradient one of `gradients_near` it.
fn mismatches(gpu: &Gpu, functions: &[Function], points: &[DVec3]) -> Vec<String> {
    let inputs: Vec<[f32; 4]> = (0..functions.len())
        .flat_map(|i| {
            points
                .iter()
                .map(move |p| [p.x as f32, p.y as f32, p.z as f32, i as f32])
        })
        .collect();
    let results = run_on_gpu(gpu, functions, &inputs);
    let mut failures = Vec::new();
    for (input, got) in inputs.iter().zip(results) {
        let f = &functions[input[3] as usize];
        let p32 = [input[0], input[1], input[2]];
        let p = DVec3::from_array(p32.map(f64::from));
        let (value, gradient) = f.value_and_gradient(p);
        let value32 = f64::from(f.eval(p32));
        let tolerance = Tolerance::at(f, p, value, gradient, value32);
        let mut check = |what: &str, got: f32, exact: f64, tol: f64| {
            let error = (f64::from(got) - exact).abs();
            if error.is_nan() || error > tol {
                failures.push(format!(
                    "{} at {p}: {what}: GPU {got} vs f64 {exact} (tolerance {tol:e})",
                    f.source()
                ));
            }
        };
        check("value", got.value, value, tolerance.value);
        check("dual value", got.dual[0], value, tolerance.value);
        let got_gradient = DVec3::new(got.dual[1].into(), got.dual[2].into(), got.dual[3].into());
        let matches = |g: &DVec3| (got_gradient - *g).abs().cmple(tolerance.gradient).all();
        if gradients_near(f, p).iter().any(matches) {
            continue;
        }
        for (axis, name) in ["d/dx", "d/dy", "d/dz"].into_iter().enumerate() {
            check(
                name,
                got.dual[axis + 1],
                gradient[axis],
                tolerance.gradient[axis],
            );
        }
    }
    failures
}

/// A random function of the whole syntax, evaluated in f64 on the CPU and
/// in the generated WGSL on the GPU, agrees, value and gradient. Functions
/// are drawn 48 at a time, so one shader runs many.
#[test]
fn random_functions_agree_on_cpu_and_gpu() {
    let gpu = common::gpu();
    let mut runner = TestRunner::new(Config {
        cases: 12,
        ..Config::default()
    });
    let strategy = (
        proptest::collection::vec(function(false), 48),
        proptest::collection::vec(point(), 16),
    );
    runner
        .run(&strategy, |(sources, points)| {
            let functions: Vec<Function> = sources
                .iter()
                .map(|s| Function::parse(s).unwrap_or_else(|e| panic!("{s}: {e}")))
                .collect();
            let failures = mismatches(&gpu, &functions, &points);
            prop_assert!(
                failures.is_empty(),
                "{} mismatches, first: {}",
                failures.len(),
                failures.join("\n")
            );
            Ok(())
        })
        .unwrap_or_else(|e| panic!("{e}"));
}

/// The functions with jumps (floor, fract, mod) and the special cases of the
/// rules (a tie of min and max, abs at 0, the real power of a negative
/// number, whole powers of negative numbers), at points away from the jumps
/// where f32 and f64 cannot fall on different sides; and a tie of `max`
/// that f32 and f64 decide differently, where either side's gradient is
/// right.
#[test]
fn jumps_and_special_cases_agree_on_cpu_and_gpu() {
    let gpu = common::gpu();
    let sources = [
        "floor(x) + fract(y) + mod(z, 0.75)",
        "mod(x, -2) + floor(-y) + fract(-z)",
        "min(x, x) + max(y, y) + abs(x - x)",
        "x^0.5 + y^2.5 + pow(z, y)",
        "x^3 + y^-3 + z^4 + x^-2",
        "clamp(x, y, z) + mix(x, y, z)",
        "x",
        "3.25",
        "pi * x",
        // Its two arguments 6e-4 apart at the last point: either branch's
        // gradient will do there (`gradients_near`).
        "max(acos(0.9 * cos(z)), (cosh(cos(x)) + atan(x)))",
        // At the last point the sum is -0.03, a cancellation that turns the
        // GPU's `asin` error (allowed 4096 ulps) into 1% of the sum, and the
        // power carries it into the gradient while the value hardly moves.
        "(((sinh(sin(y)) + asin(0.9 * sin(z))))^2 + 0.5)^-2",
    ];
    let functions: Vec<Function> = sources
        .iter()
        .map(|s| Function::parse(s).unwrap())
        .collect();
    let points = [
        DVec3::new(0.3, -1.3, 0.6),
        DVec3::new(-1.7, 2.2, -0.4),
        DVec3::new(2.6, 0.45, 1.1),
        DVec3::new(-0.2, -0.7, -1.2),
        DVec3::new(-0.3812597692012787, -0.7252069711685181, -1.040716290473938),
        DVec3::new(0.8128214478492737, 1.1268761157989502, -1.3280941247940063),
    ];
    let failures = mismatches(&gpu, &functions, &points);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
