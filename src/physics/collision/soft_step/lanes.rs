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
//!
//! # Piped
//!
//! A chain gives one sweep nothing to pair, but a sub-step has two sweeps, and the relax of
//! the stack's lower runs need not wait for the solve to reach its top. Between them each
//! body moves (`x += h v`, its turn) and each row's gap is refreshed from its two bodies'
//! poses; both are per body and per row, so the same rule orders the whole sub-step: the
//! solve's runs, then the relax's, are levelled together,
//!
//! ```text
//! level(relax of run) = 1 + max(last level of A, last level of B)   (after the whole solve)
//! ```
//!
//! a body moves once the last solve run touching it is done (after its level), and a relax
//! run refreshes its rows' gaps just before it is solved (both its bodies have moved). Every
//! body and row again sees the sequential sub-step's operations in its order, so the numbers
//! are the same bit for bit; a stack's solve of run k and relax of run k − 2 share a level and
//! go side by side. Taken only where one sweep would solve most of its rows alone (at least
//! `MIN_PIPED_RUNS` runs): a pair costs about the instructions of its two rows alone (the
//! lanes' 12 velocity registers spill), so it gains only where it fills otherwise idle
//! levels; on a pyramid, already paired, piping measured 7 % more instructions.

use super::bodies::{Bodies, Motion};
use super::f2::F2;
use super::rows::{refresh_run, Row, Rows, Run};
use super::sweep::{coefficients, solve_run};
use super::{clamp_disk, Softness};

/// One step of a scheduled sweep: a run alone, or two runs that share no body side by side
/// (with where their rows' packed constants start in [`Lanes::packed`]), each in the biased
/// solve (`true`) or the relax; or, in a piped sub-step, moving the bodies
/// `Lanes::moved[range]` a sub-step on.
#[derive(Debug, Clone, Copy)]
enum Step {
    One(usize, bool),
    Two(usize, usize, usize, [bool; 2]),
    Advance(usize, usize),
}

/// The schedule of the step's runs (module doc).
#[derive(Debug, Clone, Default)]
pub(super) struct Lanes {
    steps: Vec<Step>,
    /// Whether `steps` is a whole sub-step (solve, advance and relax piped) or one sweep.
    piped: bool,
    /// Per solver body, the level of the last run that touched it.
    last: Vec<u32>,
    /// Per entry (a run in the solve, then, piped, each run again in the relax), its level;
    /// then the entries sorted by level (stable).
    level: Vec<u32>,
    start: Vec<usize>,
    order: Vec<usize>,
    /// Piped: per solver body, the level after which it moves (its last in the solve), and
    /// the bodies sorted by it, with where each level's start.
    moves_at: Vec<u32>,
    moved: Vec<usize>,
    moved_start: Vec<usize>,
    /// The constants of each `Two` step's common rows, two rows side by side (built once per
    /// step: the sweeps load them as they are, with no lane shuffles).
    packed: Vec<Packed>,
}

/// The fewest runs a piped schedule is made for. A pair of rows costs about the instructions
/// of the two alone, so piping pays only on long chains: measured (CPU time, soft-step) a
/// stack of 10 (10 runs) breaks even at 13 % more instructions, stacks of 20 and 40 gain 4–5 %.
const MIN_PIPED_RUNS: usize = 16;

/// A counting sort of `0..keys.len()` by key (stable): `order` the indices, `start[k]` where
/// key k's begin (`start` has `top + 2` entries).
fn sort_by_level(keys: &[u32], top: usize, start: &mut Vec<usize>, order: &mut Vec<usize>) {
    start.clear();
    start.resize(top + 2, 0);
    for &l in keys {
        start[l as usize + 1] += 1;
    }
    for i in 1..start.len() {
        start[i] += start[i - 1];
    }
    order.clear();
    order.resize(keys.len(), 0);
    let mut next = start.clone();
    for (r, &l) in keys.iter().enumerate() {
        order[next[l as usize]] = r;
        next[l as usize] += 1;
    }
}

impl Lanes {
    /// Puts the runs of `rows` (over `bodies` solver bodies) in levels and pairs them: one
    /// sweep's, or, where that sweep would solve more than half its rows alone (a stack, a
    /// chain) and `may_pipe`, a whole sub-step's: the solve, each body's move and the relax
    /// (module doc, "Piped").
    #[inline(always)]
    pub fn schedule(&mut self, rows: &Rows, bodies: usize, may_pipe: bool) {
        let alone = self.plan(rows, bodies, false);
        if may_pipe && 2 * alone > rows.rows.len() && rows.runs.len() >= MIN_PIPED_RUNS {
            self.plan(rows, bodies, true);
        }
        let Lanes { steps, packed, .. } = self;
        packed.clear();
        for step in steps.iter_mut() {
            if let Step::Two(x, y, at, _) = step {
                *at = packed.len();
                let (x, y) = (&rows.runs[*x].rows, &rows.runs[*y].rows);
                let pairs = rows.rows[x.clone()].iter().zip(&rows.rows[y.clone()]);
                packed.extend(pairs.map(|(x, y)| Packed::of(x, y)));
            }
        }
    }

    /// Whether the schedule is a whole sub-step's (`substep`) rather than one sweep's.
    #[inline(always)]
    pub fn piped(&self) -> bool {
        self.piped
    }

    /// The steps of one sweep, or (`piped`) of a sub-step (`schedule`); the rows solved
    /// alone (in `One` steps).
    #[inline(always)]
    fn plan(&mut self, rows: &Rows, bodies: usize, piped: bool) -> usize {
        let Lanes {
            steps,
            piped: is_piped,
            last,
            level,
            start,
            order,
            moves_at,
            moved,
            moved_start,
            ..
        } = self;
        *is_piped = piped;
        last.clear();
        last.resize(bodies, 0);
        level.clear();
        let mut top = 0;
        let runs = &rows.runs;
        let mut place = |run: &Run, last: &mut Vec<u32>| {
            let l = 1 + run.b.map_or(last[run.a], |b| last[run.a].max(last[b]));
            last[run.a] = l;
            if let Some(b) = run.b {
                last[b] = l;
            }
            level.push(l);
            top = top.max(l as usize);
        };
        for run in runs {
            place(run, last);
        }
        if piped {
            moves_at.clear();
            moves_at.extend_from_slice(last);
            for run in runs {
                place(run, last);
            }
            sort_by_level(moves_at, top, moved_start, moved);
        }
        sort_by_level(level, top, start, order);
        steps.clear();
        let count = runs.len();
        let advance = |steps: &mut Vec<Step>, l: usize| {
            if piped && moved_start[l] < moved_start[l + 1] {
                steps.push(Step::Advance(moved_start[l], moved_start[l + 1]));
            }
        };
        advance(steps, 0);
        let mut alone = 0;
        for l in 1..=top {
            let mut pending: [Option<usize>; 2] = [None, None];
            for &e in &order[start[l]..start[l + 1]] {
                let (r, biased) = (e % count, e < count);
                let kind = usize::from(runs[r].b.is_some());
                match pending[kind].take() {
                    Some(p) => {
                        let (q, solve) = (p % count, p < count);
                        steps.push(Step::Two(q, r, 0, [solve, biased]));
                    }
                    None => pending[kind] = Some(e),
                }
            }
            for e in pending.into_iter().flatten() {
                alone += runs[e % count].rows.len();
                steps.push(Step::One(e % count, e < count));
            }
            advance(steps, l);
        }
        alone
    }

    /// One sweep over the rows in the scheduled order (not piped): the soft, biased solve
    /// (`biased`) or the rigid relax.
    #[inline(always)]
    pub fn sweep(
        &self,
        rows: &mut Rows,
        motions: &mut [Motion],
        friction: f64,
        h: f64,
        biased: bool,
    ) {
        debug_assert!(!self.piped);
        let Rows { rows, runs, .. } = rows;
        let sweep = Sweep { friction, h };
        for step in &self.steps {
            match *step {
                Step::One(r, _) => solve_run(&runs[r], rows, motions, friction, h, biased),
                Step::Two(x, y, at, _) => {
                    let packed = &self.packed[at..];
                    sweep.both(&runs[x], &runs[y], [biased; 2], packed, rows, motions);
                }
                Step::Advance(..) => {}
            }
        }
    }

    /// A whole sub-step's sweeps in the piped schedule: the biased solve, each body moved a
    /// sub-step of h on once the solve is done with it, each run's gaps refreshed and its rows
    /// relaxed once both its bodies have moved. Every body and row sees the same operations in
    /// the same order as the solve sweep, `Bodies::advance`, `Rows::refresh_gaps` and the
    /// relax sweep one after the other (module doc, "Piped").
    #[inline(always)]
    pub fn substep(&self, rows: &mut Rows, bodies: &mut Bodies, friction: f64, h: f64) {
        debug_assert!(self.piped);
        let Rows { rows, runs, .. } = rows;
        let sweep = Sweep { friction, h };
        for step in &self.steps {
            match *step {
                Step::One(r, biased) => {
                    if !biased {
                        refresh_run(&runs[r], rows, &bodies.places);
                    }
                    solve_run(&runs[r], rows, &mut bodies.motions, friction, h, biased);
                }
                Step::Two(x, y, at, biased) => {
                    for (r, biased) in [(x, biased[0]), (y, biased[1])] {
                        if !biased {
                            refresh_run(&runs[r], rows, &bodies.places);
                        }
                    }
                    let packed = &self.packed[at..];
                    let motions = &mut bodies.motions;
                    sweep.both(&runs[x], &runs[y], biased, packed, rows, motions);
                }
                Step::Advance(from, to) => {
                    for &b in &self.moved[from..to] {
                        bodies.advance_one(b, h);
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
}

impl Sweep {
    /// Runs x and y side by side (`two`), each in the solve (`biased`) or the relax.
    #[inline(always)]
    fn both(
        &self,
        x: &Run,
        y: &Run,
        biased: [bool; 2],
        packed: &[Packed],
        rows: &mut [Row],
        motions: &mut [Motion],
    ) {
        if x.b.is_some() {
            self.two::<true>(x, y, biased, packed, rows, motions);
        } else {
            self.two::<false>(x, y, biased, packed, rows, motions);
        }
    }

    /// Runs x and y (sharing no body, both with a B end or neither: `PAIR`) side by side
    /// over their common length, then each one's remaining rows alone.
    #[inline(always)]
    fn two<const PAIR: bool>(
        &self,
        x: &Run,
        y: &Run,
        biased: [bool; 2],
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
            let soft = [&x.soft, &y.soft];
            self.rows::<PAIR>([row_x, row_y], p, soft, biased, &mut a, &mut b);
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
                    biased[lane],
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
        [bx, by]: [bool; 2],
        a: &mut Wide,
        b: &mut Wide,
    ) {
        let cx = coefficients(x.gap, sx, self.h, bx);
        let cy = coefficients(y.gap, sy, self.h, by);
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
        lanes.schedule(&rows, bodies, false);
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
