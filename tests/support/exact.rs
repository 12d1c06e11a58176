//! The exact answers the intersection routines are judged by: the textbook
//! formulas evaluated in double-double arithmetic (~106 bits), on the very
//! f32 or f64 inputs the routine under test got. At that precision even the
//! textbook quadratic is accurate to far below an f64 ulp in the cases the
//! tests generate.

#![allow(dead_code)]

use glam::{DMat3, DVec3};

/// An unevaluated sum hi + lo with |lo| <= ulp(hi) / 2.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Dd {
    pub hi: f64,
    pub lo: f64,
}

fn two_sum(a: f64, b: f64) -> Dd {
    let s = a + b;
    let bb = s - a;
    Dd {
        hi: s,
        lo: (a - (s - bb)) + (b - bb),
    }
}

fn quick_two_sum(a: f64, b: f64) -> Dd {
    let s = a + b;
    Dd {
        hi: s,
        lo: b - (s - a),
    }
}

impl Dd {
    pub const ZERO: Dd = Dd { hi: 0.0, lo: 0.0 };

    pub fn new(x: f64) -> Dd {
        Dd { hi: x, lo: 0.0 }
    }

    pub fn value(self) -> f64 {
        self.hi + self.lo
    }

    pub fn add(self, o: Dd) -> Dd {
        let s = two_sum(self.hi, o.hi);
        let t = two_sum(self.lo, o.lo);
        let v = quick_two_sum(s.hi, s.lo + t.hi);
        quick_two_sum(v.hi, t.lo + v.lo)
    }

    pub fn neg(self) -> Dd {
        Dd {
            hi: -self.hi,
            lo: -self.lo,
        }
    }

    pub fn sub(self, o: Dd) -> Dd {
        self.add(o.neg())
    }

    pub fn mul(self, o: Dd) -> Dd {
        let p = self.hi * o.hi;
        // mul_add is a correctly rounded fused multiply-add in Rust.
        let e = self.hi.mul_add(o.hi, -p) + (self.hi * o.lo + self.lo * o.hi);
        quick_two_sum(p, e)
    }

    pub fn div(self, o: Dd) -> Dd {
        let q1 = self.hi / o.hi;
        let r = self.sub(o.mul(Dd::new(q1)));
        let q2 = r.hi / o.hi;
        let r = r.sub(o.mul(Dd::new(q2)));
        let q3 = r.hi / o.hi;
        quick_two_sum(q1, q2).add(Dd::new(q3))
    }

    pub fn sqrt(self) -> Dd {
        if self.hi <= 0.0 {
            return Dd::ZERO;
        }
        let x = self.hi.sqrt();
        let r = self.sub(Dd::new(x).mul(Dd::new(x)));
        quick_two_sum(x, r.hi / (2.0 * x))
    }

    pub fn lt(self, o: Dd) -> bool {
        self.sub(o).hi < 0.0
    }
}

pub type V = [Dd; 3];

pub fn v(x: DVec3) -> V {
    [Dd::new(x.x), Dd::new(x.y), Dd::new(x.z)]
}

pub fn vsub(a: V, b: V) -> V {
    [a[0].sub(b[0]), a[1].sub(b[1]), a[2].sub(b[2])]
}

pub fn dot(a: V, b: V) -> Dd {
    a[0].mul(b[0]).add(a[1].mul(b[1])).add(a[2].mul(b[2]))
}

/// `M^T x` for an f64 matrix.
pub fn mul_transpose(m: DMat3, x: V) -> V {
    std::array::from_fn(|i| dot(v(m.col(i)), x))
}

/// The ray `o + t d` and the sphere: the nearest root with t > 0 (for the
/// given, not necessarily unit, `d`).
pub struct SphereTruth {
    pub t: Option<f64>,
    /// (h / r)^2 with h the half chord: 1 through the centre, 0 at
    /// tangency, negative for a miss (1 - (distance of the line / r)^2).
    pub chord2: f64,
    /// Whether the origin is strictly inside.
    pub inside: bool,
    /// |o - centre|^2 - r^2: > 0 outside, < 0 inside.
    pub c: f64,
}

impl SphereTruth {
    /// h / r, 0 for a miss.
    pub fn half_chord(&self) -> f64 {
        self.chord2.max(0.0).sqrt()
    }
}

pub fn sphere(o: DVec3, d: DVec3, centre: DVec3, r: f64) -> SphereTruth {
    let (o, d) = (v(o), v(d));
    let f = vsub(o, v(centre));
    let a = dot(d, d);
    let b = dot(f, d);
    let rr = Dd::new(r).mul(Dd::new(r));
    let c = dot(f, f).sub(rr);
    let disc = b.mul(b).sub(a.mul(c));
    let inside = c.hi < 0.0;
    let chord2 = disc.div(a.mul(rr)).value();
    if disc.hi < 0.0 {
        return SphereTruth {
            t: None,
            chord2,
            inside,
            c: c.value(),
        };
    }
    let s = disc.sqrt();
    let t0 = b.neg().sub(s).div(a);
    let t1 = b.neg().add(s).div(a);
    let t = if t0.hi > 0.0 {
        Some(t0.value())
    } else if t1.hi > 0.0 {
        Some(t1.value())
    } else {
        None
    };
    SphereTruth {
        t,
        chord2,
        inside,
        c: c.value(),
    }
}

/// The plane through `point` with normal `n` (as given): t, the signed
/// height of `o` above it, and n.d.
pub struct PlaneTruth {
    pub t: f64,
    pub height: f64,
    pub cos: f64,
}

pub fn plane(o: DVec3, d: DVec3, point: DVec3, n: DVec3) -> PlaneTruth {
    let num = dot(vsub(v(point), v(o)), v(n));
    let den = dot(v(n), v(d));
    PlaneTruth {
        t: num.div(den).value(),
        height: num.neg().value(),
        cos: den.value(),
    }
}

/// Signed distance of `p` from the plane, along the given `n`.
pub fn plane_height(p: DVec3, point: DVec3, n: DVec3) -> f64 {
    dot(vsub(v(p), v(point)), v(n)).value()
}

/// The box `{x: |(R^T (x - centre))_i| <= half_i}` and the ray: the slab
/// test in double-double with closed slabs for d'_i = 0. `t` is the entry,
/// or the exit from inside; `slack` is t_far - t_near (> 0 through the box,
/// ~0 along an edge or a face; for a ray parallel to a slab and outside it
/// minus the distance to the slab, with `cos` 1); `cos` is |d'_axis| of the
/// face hit.
pub struct BoxTruth {
    pub t: Option<f64>,
    pub slack: f64,
    pub cos: f64,
    pub inside: bool,
}

pub fn cube(o: DVec3, d: DVec3, centre: DVec3, half: DVec3, rotation: DMat3) -> BoxTruth {
    let ol = mul_transpose(rotation, vsub(v(o), v(centre)));
    let dl = mul_transpose(rotation, v(d));
    let mut near: Option<(Dd, usize)> = None;
    let mut far: Option<(Dd, usize)> = None;
    let mut inside = true;
    for i in 0..3 {
        let h = Dd::new(half[i]);
        if ol[i].value().abs() >= half[i] {
            inside = false;
        }
        if dl[i].hi == 0.0 {
            let outside = ol[i].value().abs() - half[i];
            if outside > 0.0 {
                // Parallel to the slab and outside it: as near to a hit as
                // the distance to the slab (cos 1: the slack is a length).
                return BoxTruth {
                    t: None,
                    slack: -outside,
                    cos: 1.0,
                    inside,
                };
            }
            continue;
        }
        let ta = h.neg().sub(ol[i]).div(dl[i]);
        let tb = h.sub(ol[i]).div(dl[i]);
        let (lo, hi) = if ta.lt(tb) { (ta, tb) } else { (tb, ta) };
        if near.is_none_or(|(t, _)| t.lt(lo)) {
            near = Some((lo, i));
        }
        if far.is_none_or(|(t, _)| hi.lt(t)) {
            far = Some((hi, i));
        }
    }
    let (Some((tn, an)), Some((tf, af))) = (near, far) else {
        // Parallel to every axis: impossible for a non-zero direction.
        return BoxTruth {
            t: None,
            slack: f64::NEG_INFINITY,
            cos: 0.0,
            inside,
        };
    };
    let slack = tf.sub(tn).value();
    let (t, axis) = if slack < 0.0 {
        (None, an)
    } else if tn.hi > 0.0 {
        (Some(tn.value()), an)
    } else if tf.hi > 0.0 {
        (Some(tf.value()), af)
    } else {
        (None, an)
    };
    BoxTruth {
        t,
        slack,
        cos: dl[axis].value().abs() / dot(dl, dl).sqrt().value(),
        inside,
    }
}
