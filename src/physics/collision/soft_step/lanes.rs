//! Two runs at once: the sweeps' rows in lanes of two, without changing a bit of the result.
//!
//! A Gauss–Seidel sweep updates the bodies run by run (a run: the rows between the same two
//! bodies), in the rows' order. Two runs that share no body commute: solved in either order,
//! or at the same time, they leave every body the same. So the runs are put in levels,
//!
//! ```text
//! level(run) = 1 + max(last level of A, last level of B)      (in the rows' order)
//! ```
//!
//! and taken level by level: a run comes after every earlier run that shares a body with it
//! (its level is higher), the runs of one level share no body, and each body sees the same
//! updates in the same order as in the sequential sweep. Within a level, runs of the same
//! kind (with a B end, or against an obstacle or a fixed body) are paired, and a pair's rows
//! are solved side by side, lane 0 the first run's k-th row and lane 1 the second's (Box2D v3
//! colours its constraint graph for its SIMD lanes; this keeps the sequential order instead,
//! and with it the numbers: each lane does the scalar sweep's arithmetic, operation by
//! operation). A stack is one chain of runs (one per level, no pairs); a pyramid or a wall is
//! as wide as its courses.

use super::bodies::Motion;
use super::f2::F2;
use super::rows::{Row, Rows, Run};
use super::sweep::{coefficients, solve_run};
use super::{clamp_disk, Softness};

/// One step of a scheduled sweep: a run alone, or two runs that share no body side by side
/// (with where their rows' packed constants start in [`Lanes::packed`]).
#[derive(Debug, Clone, Copy)]
enum Step {
    One(usize),
    Two(usize, usize, usize),
}

/// The schedule of the step's runs (module doc).
#[derive(Debug, Clone, Default)]
pub(super) struct Lanes {
    steps: Vec<Step>,
    /// Per solver body, the level of the last run that touched it.
    last: Vec<u32>,
    /// Per run, its level; then the runs sorted by level (stable).
    level: Vec<u32>,
    start: Vec<usize>,
    order: Vec<usize>,
    /// The constants of each `Two` step's common rows, two rows side by side (built once per
    /// step: the sweeps load them as they are, with no lane shuffles).
    packed: Vec<Packed>,
}

impl Lanes {
    /// Puts the runs of `rows` (over `bodies` solver bodies) in levels and pairs them.
    #[inline(always)]
    pub fn schedule(&mut self, rows: &Rows, bodies: usize) {
        let Lanes {
            steps,
            last,
            level,
            start,
            order,
            packed,
        } = self;
        last.clear();
        last.resize(bodies, 0);
        level.clear();
        let mut top = 0;
        for run in &rows.runs {
            let l = 1 + run.b.map_or(last[run.a], |b| last[run.a].max(last[b]));
            last[run.a] = l;
            if let Some(b) = run.b {
                last[b] = l;
            }
            level.push(l);
            top = top.max(l as usize);
        }
        // Counting sort by level, stable.
        start.clear();
        start.resize(top + 2, 0);
        for &l in level.iter() {
            start[l as usize + 1] += 1;
        }
        for i in 1..start.len() {
            start[i] += start[i - 1];
        }
        order.clear();
        order.resize(level.len(), 0);
        let mut next = start.clone();
        for (r, &l) in level.iter().enumerate() {
            order[next[l as usize]] = r;
            next[l as usize] += 1;
        }
        steps.clear();
        for l in 1..=top {
            let mut pending: [Option<usize>; 2] = [None, None];
            for &r in &order[start[l]..start[l + 1]] {
                let kind = usize::from(rows.runs[r].b.is_some());
                match pending[kind].take() {
                    Some(p) => steps.push(Step::Two(p, r, 0)),
                    None => pending[kind] = Some(r),
                }
            }
            steps.extend(pending.into_iter().flatten().map(Step::One));
        }
        packed.clear();
        for step in steps.iter_mut() {
            if let Step::Two(x, y, at) = step {
                *at = packed.len();
                let (x, y) = (&rows.runs[*x].rows, &rows.runs[*y].rows);
                let pairs = rows.rows[x.clone()].iter().zip(&rows.rows[y.clone()]);
                packed.extend(pairs.map(|(x, y)| Packed::of(x, y)));
            }
        }
    }

    /// One sweep over the rows in the scheduled order: the soft, biased solve (`biased`) or
    /// the rigid relax.
    #[inline(always)]
    pub fn sweep(
        &self,
        rows: &mut Rows,
        motions: &mut [Motion],
        friction: f64,
        h: f64,
        biased: bool,
    ) {
        let Rows { rows, runs, .. } = rows;
        let sweep = Sweep {
            friction,
            h,
            biased,
        };
        for step in &self.steps {
            match *step {
                Step::One(r) => solve_run(&runs[r], rows, motions, friction, h, biased),
                Step::Two(x, y, at) => {
                    let packed = &self.packed[at..];
                    if runs[x].b.is_some() {
                        sweep.two::<true>(&runs[x], &runs[y], packed, rows, motions);
                    } else {
                        sweep.two::<false>(&runs[x], &runs[y], packed, rows, motions);
                    }
                }
            }
        }
    }
}

/// Two lanes of 3-vectors.
type V2 = [F2; 3];

#[inline(always)]
fn add(a: F2, b: F2) -> F2 {
    a.add(b)
}

#[inline(always)]
fn sub(a: F2, b: F2) -> F2 {
    a.sub(b)
}

#[inline(always)]
fn mul(a: F2, b: F2) -> F2 {
    a.mul(b)
}

#[inline(always)]
fn neg(a: F2) -> F2 {
    a.neg()
}

#[inline(always)]
fn add3(a: V2, b: V2) -> V2 {
    [add(a[0], b[0]), add(a[1], b[1]), add(a[2], b[2])]
}

#[inline(always)]
fn sub3(a: V2, b: V2) -> V2 {
    [sub(a[0], b[0]), sub(a[1], b[1]), sub(a[2], b[2])]
}

/// `v s`, component by component.
#[inline(always)]
fn scale(v: V2, s: F2) -> V2 {
    [mul(v[0], s), mul(v[1], s), mul(v[2], s)]
}

/// `a·b` as nalgebra sums it: `(a₀b₀ + a₁b₁) + a₂b₂`.
#[inline(always)]
fn dot(a: &V2, b: &V2) -> F2 {
    add(add(mul(a[0], b[0]), mul(a[1], b[1])), mul(a[2], b[2]))
}

/// `a×b` as nalgebra computes it.
#[inline(always)]
fn cross(a: &V2, b: &V2) -> V2 {
    [
        sub(mul(a[1], b[2]), mul(a[2], b[1])),
        sub(mul(a[2], b[0]), mul(a[0], b[2])),
        sub(mul(a[0], b[1]), mul(a[1], b[0])),
    ]
}

/// Two vectors side by side.
#[inline(always)]
fn lanes(x: &nalgebra::Vector3<f64>, y: &nalgebra::Vector3<f64>) -> V2 {
    [F2::new(x.x, y.x), F2::new(x.y, y.y), F2::new(x.z, y.z)]
}

/// Keeps lane i of `new` where `live[i]`, else of `old`.
#[inline(always)]
fn pick(live: [bool; 2], new: V2, old: V2) -> V2 {
    if live[0] && live[1] {
        return new;
    }
    [
        F2::pick(live, new[0], old[0]),
        F2::pick(live, new[1], old[1]),
        F2::pick(live, new[2], old[2]),
    ]
}

/// Two rows' constants side by side: what `Sweep::rows` reads of them besides the gap and
/// the impulses (the same numbers as the rows', in lanes 0 and 1).
#[derive(Debug, Clone, Copy)]
struct Packed {
    normal: V2,
    rn: [V2; 2],
    w_a: [V2; 3],
    w_b: [V2; 3],
    lever: V2,
    lever_other: V2,
    tangents: [V2; 2],
    inv_k: [F2; 3],
}

impl Packed {
    #[inline(always)]
    fn of(x: &Row, y: &Row) -> Packed {
        let both = |i: usize| F2::new(x.inv_k[i], y.inv_k[i]);
        let three = |a: &[nalgebra::Vector3<f64>; 3], b: &[nalgebra::Vector3<f64>; 3]| {
            [lanes(&a[0], &b[0]), lanes(&a[1], &b[1]), lanes(&a[2], &b[2])]
        };
        Packed {
            normal: lanes(&x.normal, &y.normal),
            rn: [lanes(&x.rn[0], &y.rn[0]), lanes(&x.rn[1], &y.rn[1])],
            w_a: three(&x.w_a, &y.w_a),
            w_b: three(&x.w_b, &y.w_b),
            lever: lanes(&x.lever, &y.lever),
            lever_other: lanes(&x.lever_other, &y.lever_other),
            tangents: [
                lanes(&x.tangents[0], &y.tangents[0]),
                lanes(&x.tangents[1], &y.tangents[1]),
            ],
            inv_k: [both(0), both(1), both(2)],
        }
    }
}

/// Two motions side by side.
#[derive(Debug, Clone, Copy)]
struct Wide {
    v: V2,
    omega: V2,
    inv_mass: F2,
}

impl Wide {
    #[inline(always)]
    fn of(x: &Motion, y: &Motion) -> Wide {
        Wide {
            v: lanes(&x.v, &y.v),
            omega: lanes(&x.omega, &y.omega),
            inv_mass: F2::new(x.inv_mass, y.inv_mass),
        }
    }

    #[inline(always)]
    fn lane(&self, i: usize) -> Motion {
        let v = |w: &V2| nalgebra::Vector3::new(w[0].lane(i), w[1].lane(i), w[2].lane(i));
        Motion {
            v: v(&self.v),
            omega: v(&self.omega),
            inv_mass: self.inv_mass.lane(i),
        }
    }
}

/// The sweep's constants.
struct Sweep {
    friction: f64,
    h: f64,
    biased: bool,
}

impl Sweep {
    /// Runs x and y (sharing no body, both with a B end or neither: `PAIR`) side by side
    /// over their common length, then each one's remaining rows alone.
    #[inline(always)]
    fn two<const PAIR: bool>(
        &self,
        x: &Run,
        y: &Run,
        packed: &[Packed],
        rows: &mut [Row],
        motions: &mut [Motion],
    ) {
        let still = Motion::default();
        let body = |b: Option<usize>| b.map_or(still, |b| motions[b]);
        let mut a = Wide::of(&motions[x.a], &motions[y.a]);
        let mut b = Wide::of(&body(x.b), &body(y.b));
        let common = x.rows.len().min(y.rows.len());
        for (k, p) in packed[..common].iter().enumerate() {
            let (i, j) = (x.rows.start + k, y.rows.start + k);
            let (row_x, row_y) = if i < j {
                let (low, high) = rows.split_at_mut(j);
                (&mut low[i], &mut high[0])
            } else {
                let (low, high) = rows.split_at_mut(i);
                (&mut high[0], &mut low[j])
            };
            self.rows::<PAIR>([row_x, row_y], p, [&x.soft, &y.soft], &mut a, &mut b);
        }
        for (lane, run) in [x, y].into_iter().enumerate() {
            let (mut ma, mut mb) = (a.lane(lane), b.lane(lane));
            for row in &mut rows[run.rows.start + common..run.rows.end] {
                super::sweep::solve::<PAIR>(
                    row,
                    &run.soft,
                    &mut ma,
                    &mut mb,
                    self.friction,
                    self.h,
                    self.biased,
                );
            }
            motions[run.a] = ma;
            if let Some(i) = run.b {
                motions[i] = mb;
            }
        }
    }

    /// Two rows side by side: the scalar `sweep::solve`, lane by lane, operation by operation.
    #[inline(always)]
    fn rows<const PAIR: bool>(
        &self,
        [x, y]: [&mut Row; 2],
        p: &Packed,
        [sx, sy]: [&Softness; 2],
        a: &mut Wide,
        b: &mut Wide,
    ) {
        let cx = coefficients(x.gap, sx, self.h, self.biased);
        let cy = coefficients(y.gap, sy, self.h, self.biased);
        let (bias, mass_scale, impulse_scale) = (
            F2::new(cx.0, cy.0),
            F2::new(cx.1, cy.1),
            F2::new(cx.2, cy.2),
        );
        let n = p.normal;
        let mut u = add(dot(&n, &a.v), dot(&p.rn[0], &a.omega));
        if PAIR {
            u = add(u, add(neg(dot(&n, &b.v)), dot(&p.rn[1], &b.omega)));
        }
        let lambda = F2::new(x.lambda, y.lambda);
        let inv_k = p.inv_k[0];
        let j = sub(
            mul(mul(neg(inv_k), mass_scale), add(u, bias)),
            mul(impulse_scale, lambda),
        );
        let new = [
            (x.lambda + j.lane(0)).max(0.0),
            (y.lambda + j.lane(1)).max(0.0),
        ];
        let change = sub(F2::new(new[0], new[1]), lambda);
        (x.lambda, y.lambda) = (new[0], new[1]);
        x.max_lambda = x.max_lambda.max(new[0]);
        y.max_lambda = y.max_lambda.max(new[1]);
        let live = [change.lane(0) != 0.0, change.lane(1) != 0.0];
        if live[0] || live[1] {
            let wa = p.w_a[0];
            a.v = pick(live, add3(a.v, scale(n, mul(change, a.inv_mass))), a.v);
            a.omega = pick(live, add3(a.omega, scale(wa, change)), a.omega);
            if PAIR {
                let wb = p.w_b[0];
                b.v = pick(live, add3(b.v, scale(n, mul(neg(change), b.inv_mass))), b.v);
                b.omega = pick(live, add3(b.omega, scale(wb, change)), b.omega);
            }
        }
        if self.friction > 0.0 {
            self.friction::<PAIR>([x, y], p, a, b);
        }
    }

    /// The friction of two rows side by side (after their normal updates).
    #[inline(always)]
    fn friction<const PAIR: bool>(
        &self,
        [x, y]: [&mut Row; 2],
        p: &Packed,
        a: &mut Wide,
        b: &mut Wide,
    ) {
        let bound = [self.friction * x.lambda, self.friction * y.lambda];
        let old = [x.lambda_tangent, y.lambda_tangent];
        let mut slip = add3(a.v, cross(&a.omega, &p.lever));
        if PAIR {
            slip = sub3(sub3(slip, b.v), cross(&b.omega, &p.lever_other));
        }
        let [t1, t2] = p.tangents;
        let old1 = F2::new(old[0][0], old[1][0]);
        let old2 = F2::new(old[0][1], old[1][1]);
        let n1 = sub(old1, mul(p.inv_k[1], dot(&t1, &slip)));
        let n2 = sub(old2, mul(p.inv_k[2], dot(&t2, &slip)));
        let mut new = [[n1.lane(0), n2.lane(0)], [n1.lane(1), n2.lane(1)]];
        clamp_disk(&mut new[0], bound[0]);
        clamp_disk(&mut new[1], bound[1]);
        let step = |i: usize| [new[i][0] - old[i][0], new[i][1] - old[i][1]];
        let (sx, sy) = (step(0), step(1));
        let live = [sx != [0.0; 2], sy != [0.0; 2]];
        if !(live[0] || live[1]) {
            return;
        }
        let (s1, s2) = (F2::new(sx[0], sy[0]), F2::new(sx[1], sy[1]));
        let impulse = add3(scale(t1, s1), scale(t2, s2));
        let (wa1, wa2) = (p.w_a[1], p.w_a[2]);
        a.v = pick(live, add3(a.v, scale(impulse, a.inv_mass)), a.v);
        a.omega = pick(
            live,
            add3(a.omega, add3(scale(wa1, s1), scale(wa2, s2))),
            a.omega,
        );
        if PAIR {
            let (wb1, wb2) = (p.w_b[1], p.w_b[2]);
            b.v = pick(live, sub3(b.v, scale(impulse, b.inv_mass)), b.v);
            b.omega = pick(
                live,
                add3(b.omega, add3(scale(wb1, s1), scale(wb2, s2))),
                b.omega,
            );
        }
        if live[0] {
            x.lambda_tangent = new[0];
        }
        if live[1] {
            y.lambda_tangent = new[1];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector3;

    /// A small deterministic generator (no dependency): uniform in [−1, 1).
    struct Lcg(u64);

    impl Lcg {
        fn next(&mut self) -> f64 {
            self.0 = self
                .0
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (self.0 >> 11) as f64 / (1u64 << 52) as f64 - 1.0
        }
        fn vector(&mut self) -> Vector3<f64> {
            Vector3::new(self.next(), self.next(), self.next())
        }
        fn below(&mut self, n: usize) -> usize {
            ((self.next() + 1.0) * 0.5 * n as f64) as usize % n
        }
    }

    /// Random runs over a few bodies (some against obstacles, some of unequal lengths, some
    /// rows speculative, some pushing, some sliding): the scheduled sweep in lanes leaves the
    /// motions and the rows' impulses bit for bit where the sequential sweep does.
    #[test]
    fn the_lanes_give_the_sequential_sweep_bit_for_bit() {
        let mut g = Lcg(7);
        let bodies = 9;
        let soft = [
            Softness::new(60.0, 10.0, 2.5e-4),
            Softness::new(120.0, 10.0, 2.5e-4),
        ];
        let mut rows = Rows::default();
        for _ in 0..60 {
            let a = g.below(bodies);
            let b = (g.next() > -0.4).then(|| (a + 1 + g.below(bodies - 1)) % bodies);
            let count = 1 + g.below(5);
            let start = rows.rows.len();
            for _ in 0..count {
                let normal = g.vector().normalize();
                let t1 = normal.cross(&Vector3::x()).normalize();
                let t2 = normal.cross(&t1);
                let zero = Vector3::zeros();
                let pair = b.is_some();
                rows.rows.push(Row {
                    normal,
                    tangents: [t1, t2],
                    lever: g.vector() * 0.2,
                    lever_other: if pair { g.vector() * 0.2 } else { zero },
                    rn: [g.vector(), if pair { g.vector() } else { zero }],
                    w_a: [g.vector(), g.vector(), g.vector()],
                    w_b: if pair {
                        [g.vector(), g.vector(), g.vector()]
                    } else {
                        [zero; 3]
                    },
                    inv_k: [0.3 + g.next() * 0.1, 0.4, 0.5],
                    separation: 0.0,
                    gap: g.next() * 1e-3,
                    lambda: (g.next() + 0.5).max(0.0) * 0.01,
                    lambda_tangent: [g.next() * 1e-3, g.next() * 1e-3],
                    max_lambda: 0.0,
                });
                rows.totals.push(Default::default());
            }
            rows.runs.push(Run {
                a,
                b,
                rows: start..start + count,
                soft: soft[usize::from(b.is_none())],
            });
        }
        let motions: Vec<Motion> = (0..bodies)
            .map(|i| Motion {
                v: g.vector(),
                omega: g.vector(),
                inv_mass: if i == 0 { 0.0 } else { 1.0 + g.next() * 0.5 },
            })
            .collect();
        let mut lanes = Lanes::default();
        lanes.schedule(&rows, bodies);
        assert!(lanes.steps.iter().any(|s| matches!(s, Step::Two(..))));
        let (mut wide_rows, mut wide) = (rows.clone(), motions.clone());
        let (mut one_rows, mut one) = (rows, motions);
        for biased in [true, false, true] {
            lanes.sweep(&mut wide_rows, &mut wide, 0.5, 2.5e-4, biased);
            for run in one_rows.runs.clone() {
                solve_run(&run, &mut one_rows.rows, &mut one, 0.5, 2.5e-4, biased);
            }
        }
        let bits = |v: &Vector3<f64>| v.map(f64::to_bits);
        for (w, o) in wide.iter().zip(&one) {
            assert_eq!((bits(&w.v), bits(&w.omega)), (bits(&o.v), bits(&o.omega)));
        }
        for (w, o) in wide_rows.rows.iter().zip(&one_rows.rows) {
            assert_eq!(w.lambda.to_bits(), o.lambda.to_bits());
            assert_eq!(
                w.lambda_tangent.map(f64::to_bits),
                o.lambda_tangent.map(f64::to_bits)
            );
            assert_eq!(w.max_lambda.to_bits(), o.max_lambda.to_bits());
        }
    }
}
