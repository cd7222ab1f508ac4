//! Every integrator over the whole system, when springs or joints couple the bodies: the
//! derivative is `system::System::evaluate`, the forces of all bodies at once.
//!
//! ```text
//! euler-seed, euler, symplectic-euler   each body's own update, with the system's F and τ at
//!                                       the start of the step (one evaluation)
//! rk4        k₁…k₄ = f(Y) at world stages: every body at t + dt/2 together, so a spring or a
//!            joint between two bodies is integrated to fourth order (four evaluations)
//! splitting, exact-splitting            kick(dt/2) · drift(dt) · kick(dt/2)
//! exact-splitting-4                     the Omelyan–Mryglod–Folk composition of the same
//! kick(h)    P, L += h (F, τ) at the kick's midpoint (P + h/2 F): the joints' reactions depend
//!            on the velocities (the centripetal term), a kick at the start alone would make
//!            the method first order
//! drift(h)   each body's own free flow (its method's: split or exact rotation)
//! ```
//!
//! The reaction each joint applied is averaged over the step with the method's own weights
//! (rk4: (j₁ + 2j₂ + 2j₃ + j₄)/6; a kick: its midpoint's), so `--joint` prints impulse / dt;
//! the springs' damping work is summed with the same weights.

use super::super::body::Body;
use super::super::derive::Kinematics;
use super::super::effects::Loads;
use super::super::state::{Orientation, State};
use super::super::system::{kinematics, Scratch, System};
use super::{
    euler, euler_seed, exact_splitting, exact_splitting_4, normalize, quaternion_of,
    quaternion_rate, rotation_of, splitting, symplectic_euler, Integrator,
};
use nalgebra::{Quaternion, Vector3};

/// What the forces phase computed at the start of the step.
#[derive(Debug, Clone, Copy)]
pub struct Start<'a> {
    pub kinematics: &'a [Kinematics],
    /// Total F and τ per body (effects, springs, joints).
    pub loads: &'a [Loads],
    /// Each joint's reaction on its body A.
    pub joint_loads: &'a [Loads],
    /// The springs' damping power, W.
    pub damping_power: f64,
}

/// Reused buffers, and what the step did.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Buffers {
    eval: Scratch,
    kinematics: Vec<Kinematics>,
    positions: Vec<Vector3<f64>>,
    momenta: Vec<Vector3<f64>>,
    y: Vec<Flat>,
    stage: Vec<Flat>,
    sum: Vec<Flat>,
    k: Vec<Flat>,
    /// Result: each joint's reaction on its body A, averaged over the step.
    pub joint_loads: Vec<Loads>,
    /// Result: the springs' damping work over the step, J (≤ 0).
    pub damping_work: f64,
}

/// One body's state as a vector-space element (quaternion not normalised).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Flat {
    x: Vector3<f64>,
    q: Quaternion<f64>,
    p: Vector3<f64>,
    l: Vector3<f64>,
}

impl Flat {
    #[inline]
    fn plus(&self, k: &Flat, h: f64) -> Flat {
        Flat {
            x: self.x + k.x * h,
            q: self.q + k.q * h,
            p: self.p + k.p * h,
            l: self.l + k.l * h,
        }
    }
}

/// Adds `w ×` the reactions in `from` to `into`.
fn accumulate(into: &mut [Loads], from: &[Loads], w: f64) {
    for (a, b) in into.iter_mut().zip(from) {
        a.force += b.force * w;
        a.torque += b.torque * w;
    }
}

/// One step of `integrator` over the whole system, in place.
pub fn advance(
    integrator: Integrator,
    system: &System,
    states: &mut [State],
    start: &Start,
    dt: f64,
    buffers: &mut Buffers,
) {
    buffers.joint_loads.clear();
    buffers
        .joint_loads
        .resize(start.joint_loads.len(), Loads::default());
    let bodies = system.bodies;
    match integrator {
        Integrator::EulerSeed | Integrator::Euler | Integrator::SymplecticEuler => {
            for (i, (state, body)) in states.iter_mut().zip(bodies).enumerate() {
                let (k, loads) = (&start.kinematics[i], &start.loads[i]);
                match integrator {
                    Integrator::EulerSeed => euler_seed::step(state, k, loads, dt),
                    Integrator::Euler => euler::step(state, k, loads, dt),
                    _ => symplectic_euler::step(body, state, k, loads, dt),
                }
            }
            buffers.joint_loads.copy_from_slice(start.joint_loads);
            buffers.damping_work = start.damping_power * dt;
        }
        Integrator::Rk4 => rk4(system, states, start, dt, buffers),
        Integrator::Splitting | Integrator::ExactSplitting => compose(
            integrator,
            system,
            states,
            start,
            &[0.5, 0.5],
            &[1.0],
            dt,
            buffers,
        ),
        Integrator::ExactSplitting4 => compose(
            integrator,
            system,
            states,
            start,
            &exact_splitting_4::KICKS,
            &exact_splitting_4::FLOWS,
            dt,
            buffers,
        ),
    }
}

/// Evaluates f's forces at flat states (q normalised on the way).
fn evaluate_flat(system: &System, y: &[Flat], buffers: &mut Buffers) {
    buffers.kinematics.clear();
    buffers.positions.clear();
    buffers.momenta.clear();
    for (body, s) in system.bodies.iter().zip(y) {
        buffers
            .kinematics
            .push(kinematics(body, rotation_of(&s.q), &s.p, &s.l));
        buffers.positions.push(s.x);
        buffers.momenta.push(s.l);
    }
    system.evaluate(
        &buffers.positions,
        &buffers.kinematics,
        &buffers.momenta,
        &mut buffers.eval,
    );
}

/// The stage rates from the last evaluation, at flat states `y`.
fn rates(y: &[Flat], kinematics: &[Kinematics], loads: &[Loads], out: &mut Vec<Flat>) {
    out.clear();
    out.extend(y.iter().zip(kinematics).zip(loads).map(|((s, k), f)| Flat {
        x: k.velocity,
        q: quaternion_rate(&k.angular_velocity, &s.q),
        p: f.force,
        l: f.torque,
    }));
}

/// Classical RK4 with world stages.
fn rk4(system: &System, states: &mut [State], start: &Start, dt: f64, b: &mut Buffers) {
    b.y.clear();
    b.y.extend(states.iter().map(|s| Flat {
        x: s.position,
        q: *quaternion_of(s).quaternion(),
        p: s.linear_momentum,
        l: s.angular_momentum,
    }));
    // k₁ from the forces phase.
    let mut k = std::mem::take(&mut b.k);
    rates(&b.y, start.kinematics, start.loads, &mut k);
    b.sum.clear();
    b.sum.extend_from_slice(&k);
    accumulate(&mut b.joint_loads, start.joint_loads, 1.0 / 6.0);
    let mut work = start.damping_power / 6.0;
    for (h, w) in [(0.5, 2.0), (0.5, 2.0), (1.0, 1.0)] {
        b.stage.clear();
        b.stage
            .extend(b.y.iter().zip(&k).map(|(y, ki)| y.plus(ki, h * dt)));
        let stage = std::mem::take(&mut b.stage);
        evaluate_flat(system, &stage, b);
        rates(&stage, &b.kinematics, &b.eval.loads, &mut k);
        b.stage = stage;
        for (s, ki) in b.sum.iter_mut().zip(&k) {
            *s = s.plus(ki, w);
        }
        accumulate(&mut b.joint_loads, &b.eval.joint_loads, w / 6.0);
        work += b.eval.damping_power * w / 6.0;
    }
    for (state, (y, s)) in states.iter_mut().zip(b.y.iter().zip(&b.sum)) {
        let end = y.plus(s, dt / 6.0);
        *state = State {
            position: end.x,
            orientation: Orientation::Quaternion(normalize(end.q)),
            linear_momentum: end.p,
            angular_momentum: end.l,
        };
    }
    b.damping_work = work * dt;
    b.k = k;
}

/// Kicks and drifts, alternating: `kicks[0]` · `flows[0]` · `kicks[1]` · … · `kicks[last]`,
/// each a fraction of dt.
#[allow(clippy::too_many_arguments)]
fn compose(
    integrator: Integrator,
    system: &System,
    states: &mut [State],
    start: &Start,
    kicks: &[f64],
    flows: &[f64],
    dt: f64,
    b: &mut Buffers,
) {
    b.damping_work = 0.0;
    for (i, &kick) in kicks.iter().enumerate() {
        midpoint_kick(system, states, (i == 0).then_some(start), kick * dt, b);
        if let Some(&flow) = flows.get(i) {
            for (state, body) in states.iter_mut().zip(system.bodies) {
                drift(integrator, body, state, flow * dt);
            }
        }
    }
    for j in &mut b.joint_loads {
        j.force /= dt;
        j.torque /= dt;
    }
}

/// The free flow of one body over h, as `integrator` drifts.
fn drift(integrator: Integrator, body: &Body, state: &mut State, h: f64) {
    if integrator == Integrator::Splitting {
        state.position += state.linear_momentum * (body.inv_mass * h);
        let q = splitting::free_rotation(body, &quaternion_of(state), &state.angular_momentum, h);
        state.orientation = Orientation::Quaternion(q);
    } else {
        exact_splitting::drift(body, state, h);
    }
}

/// `P, L += h (F, τ)` evaluated at `P + h/2 F, L + h/2 τ` (x and q held); the forces at the
/// kick's start are `start`'s when given. Books h × the midpoint's reactions and damping power.
fn midpoint_kick(
    system: &System,
    states: &mut [State],
    start: Option<&Start>,
    h: f64,
    b: &mut Buffers,
) {
    if start.is_none() {
        b.y.clear();
        b.y.extend(states.iter().map(flat_of));
        evaluate_flat(system, &b.y.clone(), b);
    }
    let loads: Vec<Loads> = match start {
        Some(s) => s.loads.to_vec(),
        None => b.eval.loads.clone(),
    };
    b.y.clear();
    b.y.extend(states.iter().zip(&loads).map(|(s, f)| {
        let mut y = flat_of(s);
        y.p += f.force * (h / 2.0);
        y.l += f.torque * (h / 2.0);
        y
    }));
    let mid = std::mem::take(&mut b.y);
    evaluate_flat(system, &mid, b);
    b.y = mid;
    for (state, f) in states.iter_mut().zip(&b.eval.loads) {
        state.linear_momentum += f.force * h;
        state.angular_momentum += f.torque * h;
    }
    accumulate(&mut b.joint_loads, &b.eval.joint_loads.clone(), h);
    b.damping_work += b.eval.damping_power * h;
}

/// A state as a flat element.
fn flat_of(s: &State) -> Flat {
    Flat {
        x: s.position,
        q: *quaternion_of(s).quaternion(),
        p: s.linear_momentum,
        l: s.angular_momentum,
    }
}
