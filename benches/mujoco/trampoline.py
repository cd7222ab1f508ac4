"""MuJoCo's flex trampoline, for comparison with `benches/cloth.rs`
(`world/cube-on-trampoline-21x21/implicit-euler/dt=1e-3`). Not run by CI.

    python3 -m venv /tmp/mj && /tmp/mj/bin/pip install mujoco
    /tmp/mj/bin/python benches/mujoco/trampoline.py [MODEL.xml]

The model (default `../shared/anchors/mujoco_trampoline.xml`, or the path given): a 20 x 20
flexcomp membrane pinned at its corners, a 1 kg box dropped onto it, explicit Euler at
dt = 1 ms, CG solver. Put back at the start every 2000 steps (2 s: fall, bounces) as the Rust
bench does. Prints wall and CPU microseconds per step.
"""

import os
import sys
import time

import mujoco

DEFAULT = os.path.join(
    os.path.dirname(__file__), "..", "..", "..", "shared", "anchors", "mujoco_trampoline.xml"
)

if __name__ == "__main__":
    path = sys.argv[1] if len(sys.argv) > 1 else DEFAULT
    m = mujoco.MjModel.from_xml_path(path)
    d = mujoco.MjData(m)
    runs, steps = int(os.environ.get("RUNS", "3")), 2000
    wall, cpu = time.perf_counter(), time.process_time()
    for _ in range(runs):
        mujoco.mj_resetData(m, d)
        mujoco.mj_step(m, d, nstep=steps)
    n = runs * steps
    print(
        "mujoco %s, flex trampoline 20x20 + 1 kg box, dt %g s: %.1f us/step wall, %.1f us/step CPU"
        % (
            mujoco.__version__,
            m.opt.timestep,
            (time.perf_counter() - wall) / n * 1e6,
            (time.process_time() - cpu) / n * 1e6,
        )
    )
