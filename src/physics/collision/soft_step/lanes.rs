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
//! as wide as its courses. The lanes take the normal rows; each run's friction (`patch`, one
//! block per manifold) follows, scalar, once both runs of a step are done: the runs share no
//! body, so each body still sees its run's normal rows, then its friction, as in the
//! sequential sweep.
//!
//! Two runs between two bodies each take four lanes, `[A of x, A of y, B of x, B of y]`
//! (`f4`): the four bodies' v and ω in six registers, a row's A and B ends in the same
//! instructions. A row waits on the one before it (its bodies' velocities), so a sweep is
//! bound by that chain's latency more than by its instructions: two such pairs on one level
//! are taken together, row by row in turn (a `Four` step), two chains that do not wait on
//! each other.
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
//! `MIN_PIPED_RUNS` runs): it gains only where it fills otherwise idle levels; on a pyramid,
//! already paired, piping measured 7 % more instructions.

use super::bodies::{Bodies, Motion};
use super::f2::F2;
use super::f4::Quad;
use super::rows::{refresh_run, Row, Rows, Run};
use super::patch::Patch;
use super::sweep::{coefficients, run_friction, solve_run};
use super::Softness;

/// One step of a scheduled sweep: a run alone, or two runs that share no body side by side
/// (a [`Pair`]), or two such pairs of runs between two bodies each, their rows taken in turn
/// (two chains of rows that do not wait on each other); or, in a piped sub-step, moving the
/// bodies `Lanes::moved[range]` a sub-step on.
#[derive(Debug, Clone, Copy)]
enum Step {
    One(usize, bool),
    Two(Pair),
    Four(Pair, Pair),
    Advance(usize, usize),
}

/// Two runs x and y that share no body, side by side, with where their rows' packed
/// constants start (`at`, in [`Lanes::quads`] for runs with a B end, else
/// [`Lanes::packed`]), each in the biased solve (`true`) or the relax.
#[derive(Debug, Clone, Copy)]
struct Pair {
    x: usize,
    y: usize,
    at: usize,
    biased: [bool; 2],
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
    /// step: the sweeps load them as they are, with no lane shuffles): runs against an
    /// obstacle or a fixed body in `packed`, runs between two bodies in `quads`.
    packed: Vec<Packed>,
    quads: Vec<Quads>,
}

/// The fewest runs a piped schedule is made for. A pair of rows costs about the instructions
/// of the two alone, so piping pays only on long chains: measured (CPU time, soft-step) a
/// stack of 10 (10 runs) breaks even at 13 % more instructions, stacks of 20 and 40 gain 4–5 %.
/// With the pairs in four lanes (`f4`) a piped stack of 10 still costs 4 % more instructions
/// (callgrind, 300 steps: 53.9M → 56.1M) for a time within this machine's noise.
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
        let Lanes {
            steps,
            packed,
            quads,
            ..
        } = self;
        packed.clear();
        quads.clear();
        let mut pack = |p: &mut Pair| {
            let pair = rows.runs[p.x].b.is_some();
            p.at = if pair { quads.len() } else { packed.len() };
            let (x, y) = (&rows.runs[p.x].rows, &rows.runs[p.y].rows);
            let pairs = rows.rows[x.clone()].iter().zip(&rows.rows[y.clone()]);
            if pair {
                quads.extend(pairs.map(|(x, y)| Quads::of(x, y)));
            } else {
                packed.extend(pairs.map(|(x, y)| Packed::of(x, y)));
            }
        };
        for step in steps.iter_mut() {
            match step {
                Step::Two(p) => pack(p),
                Step::Four(p, q) => {
                    pack(p);
                    pack(q);
                }
                _ => {}
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
            // A pair of runs with B ends waiting for a second on this level (a `Four`).
            let mut held: Option<Pair> = None;
            for &e in &order[start[l]..start[l + 1]] {
                let (r, biased) = (e % count, e < count);
                let kind = usize::from(runs[r].b.is_some());
                match pending[kind].take() {
                    Some(p) => {
                        let (q, solve) = (p % count, p < count);
                        let pair = Pair {
                            x: q,
                            y: r,
                            at: 0,
                            biased: [solve, biased],
                        };
                        if kind == 0 {
                            steps.push(Step::Two(pair));
                        } else if let Some(first) = held.take() {
                            steps.push(Step::Four(first, pair));
                        } else {
                            held = Some(pair);
                        }
                    }
                    None => pending[kind] = Some(e),
                }
            }
            steps.extend(held.map(Step::Two));
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
    pub fn sweep<Q: Quad>(
        &self,
        rows: &mut Rows,
        motions: &mut [Motion],
        friction: f64,
        h: f64,
        biased: bool,
    ) {
        debug_assert!(!self.piped);
        let Rows {
            rows, runs, patches, ..
        } = rows;
        let sweep = Sweep { h };
        let f = |r: usize, rows: &[Row], patches: &mut [Patch], motions: &mut [Motion]| {
            friction_alone(&runs[r], (rows, patches), motions, friction)
        };
        for step in &self.steps {
            match *step {
                Step::One(r, _) => {
                    solve_run(&runs[r], (rows, patches), motions, friction, h, biased)
                }
                Step::Two(p) => {
                    let (x, y) = (&runs[p.x], &runs[p.y]);
                    sweep.both::<Q>(self, (x, y, p.at), [biased; 2], rows, motions);
                    f(p.x, rows, patches, motions);
                    f(p.y, rows, patches, motions);
                }
                Step::Four(p, q) => {
                    let biased = [[biased; 2]; 2];
                    sweep.four::<Q>(self, [&p, &q], biased, runs, rows, motions);
                    for r in [p.x, p.y, q.x, q.y] {
                        f(r, rows, patches, motions);
                    }
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
    pub fn substep<Q: Quad>(&self, rows: &mut Rows, bodies: &mut Bodies, friction: f64, h: f64) {
        debug_assert!(self.piped);
        let Rows {
            rows, runs, patches, ..
        } = rows;
        let sweep = Sweep { h };
        let f = |r: usize, rows: &[Row], patches: &mut [Patch], motions: &mut [Motion]| {
            friction_alone(&runs[r], (rows, patches), motions, friction)
        };
        for step in &self.steps {
            match *step {
                Step::One(r, biased) => {
                    if !biased {
                        refresh_run(&runs[r], rows, &bodies.places);
                    }
                    let run = &runs[r];
                    solve_run(run, (rows, patches), &mut bodies.motions, friction, h, biased);
                }
                Step::Two(p) => {
                    refresh_relaxed(&p, runs, rows, bodies);
                    let motions = &mut bodies.motions;
                    let (x, y) = (&runs[p.x], &runs[p.y]);
                    sweep.both::<Q>(self, (x, y, p.at), p.biased, rows, motions);
                    f(p.x, rows, patches, motions);
                    f(p.y, rows, patches, motions);
                }
                Step::Four(p, q) => {
                    refresh_relaxed(&p, runs, rows, bodies);
                    refresh_relaxed(&q, runs, rows, bodies);
                    let (motions, biased) = (&mut bodies.motions, [p.biased, q.biased]);
                    sweep.four::<Q>(self, [&p, &q], biased, runs, rows, motions);
                    for r in [p.x, p.y, q.x, q.y] {
                        f(r, rows, patches, motions);
                    }
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

/// The friction of `run`'s manifolds after its normal rows were solved in lanes (the runs of
/// a step share no body, so each run's friction may follow both runs' normal rows): its two
/// motions copied in and out.
#[inline(always)]
fn friction_alone(
    run: &Run,
    (rows, patches): (&[Row], &mut [Patch]),
    motions: &mut [Motion],
    friction: f64,
) {
    if friction <= 0.0 || run.patches.is_empty() {
        return;
    }
    let mut a = motions[run.a];
    match run.b {
        Some(i) => {
            let mut b = motions[i];
            run_friction::<true>(run, (rows, patches), (&mut a, &mut b), friction);
            motions[i] = b;
        }
        None => {
            let mut b = Motion::default();
            run_friction::<false>(run, (rows, patches), (&mut a, &mut b), friction);
        }
    }
    motions[run.a] = a;
}

/// The gaps of the runs of `p` that are relaxed (piped: refreshed just before).
#[inline(always)]
fn refresh_relaxed(p: &Pair, runs: &[Run], rows: &mut [Row], bodies: &Bodies) {
    for (r, biased) in [(p.x, p.biased[0]), (p.y, p.biased[1])] {
        if !biased {
            refresh_run(&runs[r], rows, &bodies.places);
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

/// Two rows against an obstacle or a fixed body, their constants side by side: what
/// `Sweep::rows` reads of them besides the gap and the impulses (the same numbers as the
/// rows', in lanes 0 and 1).
#[derive(Debug, Clone, Copy)]
struct Packed {
    normal: V2,
    rn: V2,
    w_a: V2,
    inv_k: F2,
}

impl Packed {
    #[inline(always)]
    fn of(x: &Row, y: &Row) -> Packed {
        Packed {
            normal: lanes(&x.normal, &y.normal),
            rn: lanes(&x.rn[0], &y.rn[0]),
            w_a: lanes(&x.w_a, &y.w_a),
            inv_k: F2::new(x.inv_k, y.inv_k),
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
    h: f64,
}

impl Sweep {
    /// Runs x and y side by side (`at`: where their packed rows start), each in the solve
    /// (`biased`) or the relax: in four lanes when both have a B end, else in two.
    #[inline(always)]
    fn both<Q: Quad>(
        &self,
        lanes: &Lanes,
        (x, y, at): (&Run, &Run, usize),
        biased: [bool; 2],
        rows: &mut [Row],
        motions: &mut [Motion],
    ) {
        if x.b.is_some() {
            self.two_pairs::<Q>(x, y, biased, &lanes.quads[at..], rows, motions);
        } else {
            self.two(x, y, biased, &lanes.packed[at..], rows, motions);
        }
    }

    /// Runs x and y (sharing no body, neither with a B end) side by side over their common
    /// length, then each one's remaining rows alone.
    #[inline(always)]
    fn two(
        &self,
        x: &Run,
        y: &Run,
        biased: [bool; 2],
        packed: &[Packed],
        rows: &mut [Row],
        motions: &mut [Motion],
    ) {
        let mut a = Wide::of(&motions[x.a], &motions[y.a]);
        let common = x.rows.len().min(y.rows.len());
        for (k, p) in packed[..common].iter().enumerate() {
            let (row_x, row_y) = two_rows(rows, x.rows.start + k, y.rows.start + k);
            let soft = [&x.soft, &y.soft];
            self.rows([row_x, row_y], p, soft, biased, &mut a);
        }
        for (lane, run) in [x, y].into_iter().enumerate() {
            let (mut ma, mut still) = (a.lane(lane), Motion::default());
            self.rest::<false>(run, common, biased[lane], rows, (&mut ma, &mut still));
            motions[run.a] = ma;
        }
    }

    /// The rows of `run` after its first `common`, alone (the scalar `sweep::solve`).
    #[inline(always)]
    fn rest<const PAIR: bool>(
        &self,
        run: &Run,
        common: usize,
        biased: bool,
        rows: &mut [Row],
        (a, b): (&mut Motion, &mut Motion),
    ) {
        for row in &mut rows[run.rows.start + common..run.rows.end] {
            super::sweep::solve::<PAIR>(row, &run.soft, a, b, self.h, biased);
        }
    }

    /// Runs x and y (sharing no body, both with a B end) side by side over their common
    /// length in four lanes (`Ends`), then each one's remaining rows alone.
    #[inline(always)]
    fn two_pairs<Q: Quad>(
        &self,
        x: &Run,
        y: &Run,
        biased: [bool; 2],
        quads: &[Quads],
        rows: &mut [Row],
        motions: &mut [Motion],
    ) {
        let ends = Ends::<Q>::of(x, y, motions);
        self.finish_pairs((x, y), biased, (quads, 0), ends, rows, motions);
    }

    /// Two pairs of runs between two bodies each (`p`, `q`, sharing no body), each pair side
    /// by side in four lanes, their rows taken in turn over their common length (two chains
    /// that do not wait on each other: the second's row runs while the first's waits), then
    /// each pair finished alone (`finish_pairs`).
    #[inline(always)]
    fn four<Q: Quad>(
        &self,
        lanes: &Lanes,
        [p, q]: [&Pair; 2],
        biased: [[bool; 2]; 2],
        runs: &[Run],
        rows: &mut [Row],
        motions: &mut [Motion],
    ) {
        let (x1, y1, x2, y2) = (&runs[p.x], &runs[p.y], &runs[q.x], &runs[q.y]);
        let (mut e1, mut e2) = (Ends::<Q>::of(x1, y1, motions), Ends::<Q>::of(x2, y2, motions));
        let (q1, q2) = (&lanes.quads[p.at..], &lanes.quads[q.at..]);
        let common = |x: &Run, y: &Run| x.rows.len().min(y.rows.len());
        let both = common(x1, y1).min(common(x2, y2));
        let soft = [[&x1.soft, &y1.soft], [&x2.soft, &y2.soft]];
        for k in 0..both {
            let at = [x1, y1, x2, y2].map(|r| r.rows.start + k);
            let [a, b, c, d] = rows.get_disjoint_mut(at).expect("the runs' rows are apart");
            let ([a, b], [c, d]) = ([a, b], [c, d]);
            self.pair_normal::<Q>([a, b], &q1[k], soft[0], biased[0], &mut e1);
            self.pair_normal::<Q>([c, d], &q2[k], soft[1], biased[1], &mut e2);
        }
        self.finish_pairs((x1, y1), biased[0], (q1, both), e1, rows, motions);
        self.finish_pairs((x2, y2), biased[1], (q2, both), e2, rows, motions);
    }

    /// Runs x and y (both with a B end) in four lanes (`ends`) from their `from`-th rows
    /// over their common length, then each one's remaining rows alone; the motions written
    /// back.
    #[inline(always)]
    fn finish_pairs<Q: Quad>(
        &self,
        (x, y): (&Run, &Run),
        biased: [bool; 2],
        (quads, from): (&[Quads], usize),
        mut ends: Ends<Q>,
        rows: &mut [Row],
        motions: &mut [Motion],
    ) {
        let (xb, yb) = (x.b.unwrap_or(x.a), y.b.unwrap_or(y.a));
        let common = x.rows.len().min(y.rows.len());
        for (k, p) in quads[..common].iter().enumerate().skip(from) {
            let (row_x, row_y) = two_rows(rows, x.rows.start + k, y.rows.start + k);
            let soft = [&x.soft, &y.soft];
            self.pair_rows::<Q>([row_x, row_y], p, soft, biased, &mut ends);
        }
        for (lane, (run, b)) in [(x, xb), (y, yb)].into_iter().enumerate() {
            let mut ma = ends.lane(lane, motions[run.a].inv_mass);
            let mut mb = ends.lane(lane + 2, motions[b].inv_mass);
            self.rest::<true>(run, common, biased[lane], rows, (&mut ma, &mut mb));
            motions[run.a] = ma;
            motions[b] = mb;
        }
    }

    /// Two rows against an obstacle or a fixed body side by side: the scalar `sweep::solve`,
    /// lane by lane, operation by operation.
    #[inline(always)]
    fn rows(
        &self,
        [x, y]: [&mut Row; 2],
        p: &Packed,
        soft: [&Softness; 2],
        biased: [bool; 2],
        a: &mut Wide,
    ) {
        let n = p.normal;
        let u = add(dot(&n, &a.v), dot(&p.rn, &a.omega));
        let change = self.normal([x, y], p.inv_k, soft, biased, u);
        let live = [change.lane(0) != 0.0, change.lane(1) != 0.0];
        if live[0] || live[1] {
            let wa = p.w_a;
            a.v = pick(live, add3(a.v, scale(n, mul(change, a.inv_mass))), a.v);
            a.omega = pick(live, add3(a.omega, scale(wa, change)), a.omega);
        }
    }

    /// Two rows' normal updates from their normal rates `u` (`sweep::solve`): each row's λ
    /// and largest λ set; the change of λ.
    #[inline(always)]
    fn normal(
        &self,
        [x, y]: [&mut Row; 2],
        inv_k: F2,
        [sx, sy]: [&Softness; 2],
        [bx, by]: [bool; 2],
        u: F2,
    ) -> F2 {
        let cx = coefficients(x.gap, sx, self.h, bx);
        let cy = coefficients(y.gap, sy, self.h, by);
        let (bias, mass_scale, impulse_scale) = (
            F2::new(cx.0, cy.0),
            F2::new(cx.1, cy.1),
            F2::new(cx.2, cy.2),
        );
        let lambda = F2::new(x.lambda, y.lambda);
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
        change
    }

    /// Two rows between two bodies each, side by side in four lanes: the scalar
    /// `sweep::solve`, lane by lane, operation by operation (`Ends`).
    #[inline(always)]
    fn pair_rows<Q: Quad>(
        &self,
        [x, y]: [&mut Row; 2],
        p: &Quads,
        soft: [&Softness; 2],
        biased: [bool; 2],
        e: &mut Ends<Q>,
    ) {
        self.pair_normal::<Q>([x, y], p, soft, biased, e);
    }

    /// The normal updates of two rows between two bodies each, in four lanes.
    #[inline(always)]
    #[allow(clippy::needless_range_loop)] // k indexes four arrays of three lanes
    fn pair_normal<Q: Quad>(
        &self,
        [x, y]: [&mut Row; 2],
        p: &Quads,
        soft: [&Softness; 2],
        biased: [bool; 2],
        e: &mut Ends<Q>,
    ) {
        let n = p.normal.each_ref().map(Q::load);
        // Lanes [n·v_A, −n·v_B] + [(r_A×n)·ω_A, (r_B×(−n))·ω_B], then the halves added: the
        // scalar `u = (n·v_A + (r_A×n)·ω_A) + (−n·v_B + (r_B×(−n))·ω_B)`.
        let ends = dot4(&p.normal, &e.v).neg_hi().add(dot4(&p.rn, &e.omega));
        let u = add(ends.lo(), ends.hi());
        let change = self.normal([x, y], p.inv_k, soft, biased, u);
        let live = [change.lane(0) != 0.0, change.lane(1) != 0.0];
        if live[0] || live[1] {
            // B: n (j·(−1/M_B)) = n ((−j)/M_B) and I_B⁻¹(r_B×(−n)) j, bit for bit.
            let c = Q::join(change, change);
            let dv = c.mul(e.mass);
            for k in 0..3 {
                let w = Q::load(&p.w[k]);
                e.v[k] = pick4(live, e.v[k].add(n[k].mul(dv)), e.v[k]);
                e.omega[k] = pick4(live, e.omega[k].add(w.mul(c)), e.omega[k]);
            }
        }
    }

}

/// Rows i and j (i ≠ j) of `rows`, both mutable.
#[inline(always)]
fn two_rows(rows: &mut [Row], i: usize, j: usize) -> (&mut Row, &mut Row) {
    if i < j {
        let (low, high) = rows.split_at_mut(j);
        (&mut low[i], &mut high[0])
    } else {
        let (low, high) = rows.split_at_mut(i);
        (&mut high[0], &mut low[j])
    }
}

/// Four lanes of 3-vectors, by component.
type V4<Q> = [Q; 3];

/// `a·b` lane by lane as nalgebra sums it: `(a₀b₀ + a₁b₁) + a₂b₂` (a loaded as it goes).
#[inline(always)]
fn dot4<Q: Quad>(a: &[[f64; 4]; 3], b: &V4<Q>) -> Q {
    let p = |k: usize| Q::load(&a[k]).mul(b[k]);
    p(0).add(p(1)).add(p(2))
}

/// Keeps lanes 0 and 2 of `new` where `live[0]`, 1 and 3 where `live[1]`, else of `old`.
#[inline(always)]
fn pick4<Q: Quad>(live: [bool; 2], new: Q, old: Q) -> Q {
    if live[0] && live[1] {
        return new;
    }
    Q::pick(live, new, old)
}

/// The four bodies of two runs between two bodies each, in lanes
/// `[A of x, A of y, B of x, B of y]`: v and ω by component, and `[1/M_A, 1/M_A, −1/M_B,
/// −1/M_B]` (an impulse j on A is −j on B).
#[derive(Debug, Clone, Copy)]
struct Ends<Q> {
    v: V4<Q>,
    omega: V4<Q>,
    mass: Q,
}

impl<Q: Quad> Ends<Q> {
    /// The motions of runs x and y's ends in lanes.
    #[inline(always)]
    fn of(x: &Run, y: &Run, motions: &[Motion]) -> Ends<Q> {
        let (xb, yb) = (x.b.unwrap_or(x.a), y.b.unwrap_or(y.a));
        Ends::of_four([&motions[x.a], &motions[y.a], &motions[xb], &motions[yb]])
    }

    /// The four motions `[A of x, A of y, B of x, B of y]` in lanes (built from halves in
    /// registers, not stored and loaded back).
    #[inline(always)]
    fn of_four([ax, ay, bx, by]: [&Motion; 4]) -> Ends<Q> {
        let four = |x: &nalgebra::Vector3<f64>, y, z, w| -> V4<Q> {
            let half = |a: &nalgebra::Vector3<f64>, b: &nalgebra::Vector3<f64>, k: usize| {
                F2::new(a[k], b[k])
            };
            std::array::from_fn(|k| Q::join(half(x, y, k), half(z, w, k)))
        };
        Ends {
            v: four(&ax.v, &ay.v, &bx.v, &by.v),
            omega: four(&ax.omega, &ay.omega, &bx.omega, &by.omega),
            mass: Q::join(
                F2::new(ax.inv_mass, ay.inv_mass),
                F2::new(-bx.inv_mass, -by.inv_mass),
            ),
        }
    }

    /// Lane `lane`'s motion (0, 1: A of x, y; 2, 3: B of x, y), its 1/M `inv_mass`.
    #[inline(always)]
    fn lane(&self, lane: usize, inv_mass: f64) -> Motion {
        let half = |q: Q| if lane < 2 { q.lo() } else { q.hi() };
        let get = |q: &V4<Q>| {
            nalgebra::Vector3::new(
                half(q[0]).lane(lane % 2),
                half(q[1]).lane(lane % 2),
                half(q[2]).lane(lane % 2),
            )
        };
        Motion {
            v: get(&self.v),
            omega: get(&self.omega),
            inv_mass,
        }
    }
}

/// Two rows between two bodies each side by side in four lanes `[A of x, A of y, B of x,
/// B of y]` (`Ends`): the same numbers as the rows', by component.
#[derive(Debug, Clone, Copy)]
#[repr(C, align(32))]
struct Quads {
    /// n in all four lanes.
    normal: [[f64; 4]; 3],
    /// `r_A×n` and `r_B×(−n)`.
    rn: [[f64; 4]; 3],
    /// `I_A⁻¹(r_A×n)` and `I_B⁻¹(r_B×(−n))`.
    w: [[f64; 4]; 3],
    /// 1/k of rows x and y.
    inv_k: F2,
}

impl Quads {
    #[inline(always)]
    fn of(x: &Row, y: &Row) -> Quads {
        let four = |a: &nalgebra::Vector3<f64>,
                    b: &nalgebra::Vector3<f64>,
                    c: &nalgebra::Vector3<f64>,
                    d: &nalgebra::Vector3<f64>| {
            std::array::from_fn(|k| [a[k], b[k], c[k], d[k]])
        };
        Quads {
            normal: four(&x.normal, &y.normal, &x.normal, &y.normal),
            rn: four(&x.rn[0], &y.rn[0], &x.rn[1], &y.rn[1]),
            w: four(&x.w_a, &y.w_a, &x.w_b, &y.w_b),
            inv_k: F2::new(x.inv_k, y.inv_k),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::f4::Plain;
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
    /// rows speculative, some pushing, some sliding): the scheduled sweep in lanes (two and
    /// four, in both builds of the four) leaves the motions and the rows' impulses bit for bit
    /// where the sequential sweep does.
    #[test]
    fn the_lanes_give_the_sequential_sweep_bit_for_bit() {
        let mut g = Lcg(7);
        let mut f = Lcg(13);
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
                let zero = Vector3::zeros();
                let pair = b.is_some();
                rows.rows.push(Row {
                    normal,
                    lever: g.vector() * 0.2,
                    lever_other: if pair { g.vector() * 0.2 } else { zero },
                    rn: [g.vector(), if pair { g.vector() } else { zero }],
                    // Drawn as when a row had three axes (the tangents' unused), so that
                    // the runs, and the schedule, are the ones drawn before.
                    w_a: [g.vector(), g.vector(), g.vector()][0],
                    w_b: if pair {
                        [g.vector(), g.vector(), g.vector()][0]
                    } else {
                        zero
                    },
                    inv_k: 0.3 + g.next() * 0.1,
                    reach: (f.next() + 1.0) * 0.1,
                    separation: 0.0,
                    gap: g.next() * 1e-3,
                    lambda: (g.next() + 0.5).max(0.0) * 0.01,
                    max_lambda: 0.0,
                });
                // The two tangent impulses a row drew before.
                g.next();
                g.next();
                rows.totals.push(Default::default());
            }
            // One manifold, or two when the run has more than two rows (drawn from their own
            // generator: the rows and runs are the ones drawn before manifolds were).
            let first = rows.patches.len();
            let split = if count > 2 { start + 2 } else { start + count };
            for span in [start..split, split..start + count] {
                if span.is_empty() {
                    continue;
                }
                let pair = b.is_some();
                let zero = Vector3::zeros();
                let normal = rows.rows[span.start].normal;
                let t1 = normal.cross(&Vector3::x()).normalize();
                let t2 = normal.cross(&t1);
                let three = |g: &mut Lcg| [g.vector(), g.vector(), g.vector()];
                rows.patches.push(Patch {
                    rows: span,
                    normal,
                    tangents: [t1, t2],
                    lever: f.vector() * 0.2,
                    lever_other: if pair { f.vector() * 0.2 } else { zero },
                    w_a: three(&mut f),
                    w_b: if pair { three(&mut f) } else { [zero; 3] },
                    inv_k: [0.4, 0.5, 0.6],
                    lambda: [f.next() * 1e-3, f.next() * 1e-3, f.next() * 1e-4],
                });
                rows.patch_totals.push(Default::default());
            }
            rows.runs.push(Run {
                a,
                b,
                rows: start..start + count,
                patches: first..rows.patches.len(),
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
        let pairs = |pair: bool| {
            let of = |p: &Pair| usize::from(rows.runs[p.x].b.is_some() == pair);
            let count = |s: &Step| match s {
                Step::Two(p) => of(p),
                Step::Four(p, q) => of(p) + of(q),
                _ => 0,
            };
            lanes.steps.iter().map(count).sum::<usize>()
        };
        assert!(pairs(true) > 0 && pairs(false) > 0);
        let four = |s: &Step| matches!(s, Step::Four(..));
        assert!(lanes.steps.iter().any(four), "no two pairs of runs taken together");
        let (mut one_rows, mut one) = (rows.clone(), motions.clone());
        for biased in [true, false, true] {
            for run in one_rows.runs.clone() {
                let both = (&mut one_rows.rows[..], &mut one_rows.patches[..]);
                solve_run(&run, both, &mut one, 0.5, 2.5e-4, biased);
            }
        }
        let check = |wide_rows: &Rows, wide: &[Motion]| {
            let bits = |v: &Vector3<f64>| v.map(f64::to_bits);
            for (w, o) in wide.iter().zip(&one) {
                assert_eq!((bits(&w.v), bits(&w.omega)), (bits(&o.v), bits(&o.omega)));
            }
            for (w, o) in wide_rows.rows.iter().zip(&one_rows.rows) {
                assert_eq!(w.lambda.to_bits(), o.lambda.to_bits());
                assert_eq!(w.max_lambda.to_bits(), o.max_lambda.to_bits());
            }
            for (w, o) in wide_rows.patches.iter().zip(&one_rows.patches) {
                assert_eq!(w.lambda.map(f64::to_bits), o.lambda.map(f64::to_bits));
            }
        };
        let (mut wide_rows, mut wide) = (rows.clone(), motions.clone());
        for biased in [true, false, true] {
            lanes.sweep::<Plain>(&mut wide_rows, &mut wide, 0.5, 2.5e-4, biased);
        }
        check(&wide_rows, &wide);
        #[cfg(target_arch = "x86_64")]
        if crate::physics::simd::avx2() {
            let (mut wide_rows, mut wide) = (rows, motions);
            for biased in [true, false, true] {
                lanes.sweep::<super::super::f4::Avx>(&mut wide_rows, &mut wide, 0.5, 2.5e-4, biased);
            }
            check(&wide_rows, &wide);
        }
    }
}
