//! Fixed things: a B that never moves — an obstacle of the scene or a fixed body — as one static
//! entry of the shape table, the one way detection (`contacts`) and `seed` reach it.
//!
//! A [`Fixed`] is a shape at a pose that takes no impulse, with its row label ([`Against`]) and
//! its solver body entry ([`CollideInput::end`]). The fixed things of a step are the obstacles
//! in the scene's order, then the fixed bodies in the world's ([`CollideInput::fixed_things`],
//! the order of `Snapshot::fixed`). What detection asks of one, and how each answers:
//!
//! | asks | obstacle | fixed body |
//! |---|---|---|
//! | [`contact`](Fixed::contact): A's shape against it | its kind's (`Obstacle::contact`: the shape table's pair, or the kind's own) | the shape table's pair (`shape_shape`) |
//! | [`sweep`](Fixed::sweep): a fast A against it (`sweep`) | still at its pose; a half-space is never tunnelled | its two (unmoved) states |
//! | [`beyond`](Fixed::beyond): too far to touch | never (an obstacle may be unbounded) | bounding spheres apart by more than the margin |
//! | [`inside`](Fixed::inside): a point in it | its kind's exact formula (`detect`) | the shape table's closest point (`point_shape`) |
//! | [`exact`](Fixed::exact): the report's vertex test | its kind (the lessons' numbers) | none: the pair alone |
//! | [`lever`](Fixed::lever): r_B = p − x_B | 0 | p − x_B |
//!
//! The solvers need none of this: they reach B through its entry alone (a static solver body,
//! 1/M = 0, I⁻¹ = 0, at rest).

use super::detect::Penetration;
use super::geometry::{point_shape, shape_shape, ContactPoint, Pose, Shape};
use super::sweep;
use super::{Against, CollideInput, Obstacle};
use crate::physics::state::State;
use nalgebra::Vector3;

/// A B that never moves: its label, its solver body entry and what it is.
#[derive(Debug, Clone, Copy)]
pub struct Fixed<'a> {
    /// What the row says B is (front ends, warm starts).
    pub against: Against,
    /// B's entry in the solver body table ([`CollideInput::end`]).
    pub end: usize,
    thing: Thing<'a>,
}

/// What a fixed thing is.
#[derive(Debug, Clone, Copy)]
enum Thing<'a> {
    /// An obstacle of the scene (`[[obstacle]]`): a kind of `obstacle/kinds/`.
    Obstacle(&'a Obstacle),
    /// A fixed body: its shape at its state, and its state at the start of the step (the same).
    Body {
        shape: &'a Shape,
        state: &'a State,
        before: &'a State,
    },
}

impl CollideInput<'_> {
    /// B's entry in the solver body table: the world's bodies first, in order, then one static
    /// solver body per obstacle (`SolverBody::fixed_thing`), in the scene's order.
    ///
    /// ```text
    /// Body(j)      → j
    /// Obstacle(o)  → bodies + o
    /// ```
    pub fn end(&self, against: Against) -> usize {
        match against {
            Against::Body(b) => b,
            Against::Obstacle(o) => self.bodies.len() + o,
        }
    }

    /// Obstacle `o` as a fixed thing.
    pub fn obstacle(&self, o: usize) -> Fixed<'_> {
        let against = Against::Obstacle(o);
        Fixed {
            against,
            end: self.end(against),
            thing: Thing::Obstacle(&self.obstacles[o]),
        }
    }

    /// Body `j` at `states[j]` as a fixed thing, if it is fixed and has a shape.
    pub fn fixed_body<'s>(&'s self, j: usize, states: &'s [State]) -> Option<Fixed<'s>> {
        let body = &self.bodies[j];
        let shape = body.shape.as_ref().filter(|_| body.fixed)?;
        Some(Fixed {
            against: Against::Body(j),
            end: j,
            thing: Thing::Body {
                shape,
                state: &states[j],
                before: &self.before[j],
            },
        })
    }

    /// Every fixed thing: the obstacles, then the fixed bodies (module doc).
    pub fn fixed_things<'s>(&'s self, states: &'s [State]) -> impl Iterator<Item = Fixed<'s>> {
        (0..self.obstacles.len())
            .map(|o| self.obstacle(o))
            .chain((0..self.bodies.len()).filter_map(move |j| self.fixed_body(j, states)))
    }
}

impl Fixed<'_> {
    /// The report's exact vertex test, if this fixed thing has one: an obstacle's kind (its
    /// `inside`, `swept` and `near`, `detect`'s formulas). A fixed body has none: bodies meet
    /// it through the pair alone.
    #[inline]
    pub fn exact(&self) -> Option<&Obstacle> {
        match self.thing {
            Thing::Obstacle(o) => Some(o),
            Thing::Body { .. } => None,
        }
    }

    /// Appends the contact points of shape A at `pa` against it (B) to `out`.
    pub fn contact(&self, a: &Shape, pa: &Pose, margin: f64, out: &mut Vec<ContactPoint>) {
        match self.thing {
            Thing::Obstacle(o) => o.contact(a, pa, margin, out),
            Thing::Body { shape, state, .. } => {
                shape_shape(a, pa, shape, &pose_of(state), margin, out)
            }
        }
    }

    /// A fast A (shape `a`, from `before` to `state`) swept against it (`sweep`): true when
    /// the sweep answered, with its rows in `out`; false when detection at the end pose is
    /// right (A not fast, or a half-space, which nothing tunnels).
    ///
    /// ```text
    /// swept when  A's points may move more than FAST · min(τ_A, τ_B) over the step
    /// ```
    pub fn sweep(
        &self,
        a: &Shape,
        before: &State,
        state: &State,
        margin: f64,
        out: &mut Vec<ContactPoint>,
    ) -> bool {
        let side_a = |thin_b: f64| {
            let thin = sweep::half_thickness(a).min(thin_b);
            sweep::may_exceed(before, state, a, sweep::FAST * thin).then(|| sweep::Side {
                shape: a,
                path: sweep::Path::new(before, state, a.bounding_radius()),
            })
        };
        match self.thing {
            Thing::Obstacle(o) => {
                if o.is_half_space() {
                    return false;
                }
                let (shape, at) = o.shape();
                let Some(side_a) = side_a(sweep::half_thickness(&shape)) else {
                    return false;
                };
                let side_b = sweep::Side {
                    shape: &shape,
                    path: sweep::Path::still(&at),
                };
                sweep::swept_rows(&side_a, &side_b, margin, out)
            }
            Thing::Body {
                shape,
                state: state_b,
                before: before_b,
            } => {
                let Some(side_a) = side_a(sweep::half_thickness(shape)) else {
                    return false;
                };
                let side_b = sweep::Side {
                    shape,
                    path: sweep::Path::new(before_b, state_b, shape.bounding_radius()),
                };
                sweep::swept_rows(&side_a, &side_b, margin, out)
            }
        }
    }

    /// Whether a shape of bounding radius `radius` at `position` is too far to touch it within
    /// `margin` (the bounding spheres apart).
    #[inline]
    pub fn beyond(&self, position: &Vector3<f64>, radius: f64, margin: f64) -> bool {
        match self.thing {
            Thing::Obstacle(_) => false,
            Thing::Body { shape, state, .. } => {
                let reach = radius + shape.bounding_radius() + margin;
                (position - state.position).norm_squared() > reach * reach
            }
        }
    }

    /// Static test: is `p` inside? Depth > 0 and the outward normal.
    pub fn inside(&self, p: &Vector3<f64>) -> Option<Penetration> {
        match self.thing {
            Thing::Obstacle(o) => o.inside(p),
            Thing::Body { shape, state, .. } => point_shape(p, shape, &pose_of(state), 0.0)
                .filter(|c| c.depth > 0.0)
                .map(|c| Penetration {
                    depth: c.depth,
                    normal: c.normal,
                }),
        }
    }

    /// The lever arm r_B from B's barycenter to the point `p`: zero for an obstacle (it has
    /// none; its rows have always carried zero).
    #[inline]
    pub fn lever(&self, p: &Vector3<f64>) -> Vector3<f64> {
        match self.thing {
            Thing::Obstacle(_) => Vector3::zeros(),
            Thing::Body { state, .. } => p - state.position,
        }
    }
}

/// Where a body's shape is.
pub fn pose_of(state: &State) -> Pose {
    Pose {
        position: state.position,
        rotation: state.orientation.matrix(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::physics::body::Body;
    use crate::physics::collision::broad_phase::BroadPhase;
    use crate::physics::collision::obstacle::{AlignedBox, Ground, Sphere};
    use crate::physics::collision::{contacts, Contact, ContactModel, Impacts, Response};
    use crate::physics::effects::Loads;

    /// Runs `f` on a collide input over `bodies` at `before` and `obstacles`.
    fn with_input<R>(
        bodies: &[Body],
        obstacles: &[Obstacle],
        before: &[State],
        f: impl FnOnce(&CollideInput) -> R,
    ) -> R {
        let model = ContactModel {
            response: Response::Impulse,
            restitution: 0.0,
            friction: 0.5,
            impacts: Impacts::default(),
        };
        let loads = vec![Loads::default(); bodies.len()];
        let initial: Vec<_> = before.iter().map(|s| s.position).collect();
        let input = CollideInput {
            bodies,
            obstacles,
            model: &model,
            before,
            loads: &loads,
            initial_positions: &initial,
            context: crate::physics::collision::StepContext::new(
                1e-2,
                Some(Vector3::new(0.0, -9.81, 0.0)),
                Some(&model),
            ),
            joined: &[],
            joints: None,
            recorded: None,
        };
        f(&input)
    }

    fn at(position: Vector3<f64>) -> State {
        State {
            position,
            ..State::at_rest()
        }
    }

    fn cube() -> Body {
        Body::solid_box(Vector3::repeat(0.2), 1.0).unwrap()
    }

    /// A slab 2 × 0.02 × 2 m whose top face is y = 0, as a fixed body and as an obstacle.
    fn slab() -> (Body, State, Obstacle) {
        let body = Body::solid_box(Vector3::new(2.0, 0.02, 2.0), 1.0)
            .unwrap()
            .fixed();
        let state = at(Vector3::new(0.0, -0.01, 0.0));
        let obstacle = Obstacle::AlignedBox(AlignedBox {
            min: Vector3::new(-1.0, -0.02, -1.0),
            max: Vector3::new(1.0, 0.0, 1.0),
        });
        (body, state, obstacle)
    }

    #[test]
    fn the_fixed_things_are_the_obstacles_then_the_fixed_bodies_each_with_its_entry() {
        let ball = Body::sphere(0.3, 1.0, false).unwrap().fixed();
        let bodies = [cube(), slab().0, cube(), ball];
        let obstacles = [
            Obstacle::Ground(Ground { height: 0.0 }),
            Obstacle::Sphere(Sphere {
                center: Vector3::zeros(),
                radius: 1.0,
            }),
        ];
        let states = [State::at_rest(); 4];
        let found: Vec<(Against, usize, bool)> = with_input(&bodies, &obstacles, &states, |i| {
            i.fixed_things(&states)
                .map(|f| (f.against, f.end, f.exact().is_some()))
                .collect()
        });
        assert_eq!(
            found,
            [
                (Against::Obstacle(0), 4, true),
                (Against::Obstacle(1), 5, true),
                (Against::Body(1), 1, false),
                (Against::Body(3), 3, false),
            ]
        );
    }

    #[test]
    fn a_fixed_box_answers_the_point_test_as_the_box_obstacle_with_its_faces() {
        // min/max and centre ± half agree exactly here (binary fractions).
        let body = Body::solid_box(Vector3::new(1.0, 0.5, 2.0), 1.0)
            .unwrap()
            .fixed();
        let states = [at(Vector3::new(0.25, 0.5, -0.5))];
        let obstacles = [Obstacle::AlignedBox(AlignedBox {
            min: Vector3::new(-0.25, 0.25, -1.5),
            max: Vector3::new(0.75, 0.75, 0.5),
        })];
        with_input(&[body], &obstacles, &states, |input| {
            let things: Vec<Fixed> = input.fixed_things(&states).collect();
            let (obstacle, fixed_body) = (&things[0], &things[1]);
            let (mut inside, mut outside) = (0, 0);
            for i in 0..11 {
                for j in 0..11 {
                    for k in 0..11 {
                        let p = Vector3::new(
                            -0.6 + 0.151 * i as f64,
                            0.013 + 0.097 * j as f64,
                            -1.9 + 0.289 * k as f64,
                        );
                        match (obstacle.inside(&p), fixed_body.inside(&p)) {
                            (Some(o), Some(b)) => {
                                inside += 1;
                                assert!((o.depth - b.depth).abs() < 1e-12, "{p:?}");
                                assert!((o.normal - b.normal).norm() < 1e-9, "{p:?}");
                            }
                            (None, None) => outside += 1,
                            other => panic!("{p:?}: {other:?}"),
                        }
                    }
                }
            }
            assert!(inside > 50 && outside > 50, "{inside} in, {outside} out");
        });
    }

    /// The rows of `bodies` at `states` (started from `before`) against `obstacles`.
    fn rows(
        bodies: &[Body],
        obstacles: &[Obstacle],
        before: &[State],
        states: &[State],
    ) -> Vec<Contact> {
        with_input(bodies, obstacles, before, |input| {
            let mut out = Vec::new();
            let mut broad = BroadPhase::default();
            contacts::find(input, states, 1e-3, &mut out, &mut Vec::new(), &mut broad);
            out
        })
    }

    #[test]
    fn a_cube_sunk_into_a_slab_meets_the_obstacle_and_the_fixed_body_alike() {
        // The cube's bottom face 1 mm into the slab's top y = 0: four points 1 mm deep, +y,
        // by the vertex test (obstacle) and by the face manifold (fixed body).
        let (slab, slab_state, obstacle) = slab();
        let cube_state = at(Vector3::new(0.1, 0.1 - 1e-3, -0.2));
        let on_obstacle = rows(&[cube()], &[obstacle], &[cube_state], &[cube_state]);
        let both = [cube_state, slab_state];
        let on_body = rows(&[cube(), slab], &[], &both, &both);
        for (found, other) in [(&on_obstacle, 1), (&on_body, 1)] {
            assert_eq!(found.len(), 4, "{found:?}");
            for c in found.iter() {
                assert_eq!((c.body, c.other), (0, other));
                assert!((c.depth - 1e-3).abs() < 1e-12, "{}", c.depth);
                assert_eq!(c.normal, Vector3::y());
            }
        }
        assert_eq!(on_obstacle[0].against, Against::Obstacle(0));
        assert_eq!(on_body[0].against, Against::Body(1));
        // The fixed body's rows carry r_B from its barycenter; an obstacle's none.
        assert!(on_obstacle
            .iter()
            .all(|c| c.lever_other == Vector3::zeros()));
        assert!(on_body
            .iter()
            .all(|c| c.lever_other == c.point - slab_state.position));
    }

    #[test]
    fn a_fast_ball_is_swept_into_a_thin_fixed_slab_as_into_the_obstacle() {
        // 0.6 m in one step across a 2 cm slab: never inside at either end, caught by the sweep.
        let (slab, slab_state, obstacle) = slab();
        let ball = Body::sphere(0.05, 1.0, false).unwrap();
        let (from, to) = (
            at(Vector3::new(0.0, 0.3, 0.0)),
            at(Vector3::new(0.0, -0.3, 0.0)),
        );
        let on_obstacle = rows(std::slice::from_ref(&ball), &[obstacle], &[from], &[to]);
        let on_body = rows(&[ball, slab], &[], &[from, slab_state], &[to, slab_state]);
        for found in [&on_obstacle, &on_body] {
            assert!(!found.is_empty());
            for c in found.iter() {
                assert!((c.normal - Vector3::y()).norm() < 1e-9, "{c:?}");
                // Carried to the end pose: the ball's centre is 0.3 + 0.05 m below the top.
                assert!((c.depth - 0.35).abs() < 0.02, "{c:?}");
            }
        }
    }
}
