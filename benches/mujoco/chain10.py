"""MuJoCo's 10-link chain, for comparison with `benches/joints.rs` (`chain-10`). Not run by CI.

    python3 -m venv /tmp/mj && /tmp/mj/bin/pip install mujoco
    /tmp/mj/bin/python benches/mujoco/chain10.py

Ten 0.5 m links (0.5 x 0.05 x 0.05 m boxes, 0.1 kg) end to end from a world pivot, released
horizontal, no contacts, RK4 at dt = 1 ms; put back at the start every 2000 steps as the
Rust bench does. Prints wall and CPU microseconds per step for hinge and for ball joints.
"""

import time

import mujoco


def chain(n, joint):
    body = ""
    for i in reversed(range(n)):
        body = (
            '<body pos="%g 0 0"><joint type="%s"/>'
            '<geom type="box" size="0.25 0.025 0.025" pos="0.25 0 0" mass="0.1"'
            ' contype="0" conaffinity="0"/>%s</body>' % (0.0 if i == 0 else 0.5, joint, body)
        )
    return (
        '<mujoco><option timestep="0.001" integrator="RK4" gravity="0 -9.81 0"/>'
        "<worldbody>%s</worldbody></mujoco>" % body
    )


if __name__ == "__main__":
    for joint in ["hinge", "ball"]:
        m = mujoco.MjModel.from_xml_string(chain(10, joint))
        d = mujoco.MjData(m)
        runs, steps = 30, 2000
        wall, cpu = time.perf_counter(), time.process_time()
        for _ in range(runs):
            mujoco.mj_resetData(m, d)
            mujoco.mj_step(m, d, nstep=steps)
        n = runs * steps
        print(
            "mujoco %s, 10-link %s chain, RK4, dt 1 ms: %.2f us/step wall, %.2f us/step CPU"
            % (
                mujoco.__version__,
                joint,
                (time.perf_counter() - wall) / n * 1e6,
                (time.process_time() - cpu) / n * 1e6,
            )
        )
