"""The Maneuverability Map of the paper's roundabout (S2) from Python, drawn with matplotlib.

    PYTHONPATH=build/release/python /usr/bin/python3 examples/python/roundabout_map.py out/roundabout-map.png

Runs the built-in scenario under ADJ, then under a constant forecast time of 0.5 s, and draws the
ego's MI− and MI+ over time and forecast time, with its speed under both policies (docs/python.md).
"""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import maneuvermap as mm  # noqa: E402


def main(out):
    adj = mm.sim.run("s2-roundabout", jobs=2)
    constant = mm.sim.run("s2-roundabout", policy=mm.forecast_policy.parse("const:0.5"), jobs=2)
    ego = adj.agents[0].name
    m = adj.map(ego)
    print(f"{ego}: {len(m.times)} planning steps, least room "
          f"{np.max([m.mi_brake, m.mi_accelerate], axis=0).min():.3f}, "
          f"crash under ADJ: {adj.metrics[0].crash}, under const:0.5: {constant.metrics[0].crash}")

    fig, axes = plt.subplots(3, 1, figsize=(8, 9), sharex=True, constrained_layout=True)
    extent = [m.times[0], m.times[-1], m.forecast_times[0], m.forecast_times[-1]]
    for ax, values, label in ((axes[0], m.mi_brake, "MI− (brake and steer)"),
                              (axes[1], m.mi_accelerate, "MI+ (accelerate and steer)")):
        image = ax.imshow(values.T, origin="lower", aspect="auto", extent=extent, vmin=0.0, vmax=1.0,
                          cmap="viridis", interpolation="nearest")
        ax.plot(m.times, m.forecast_time, color="white", linewidth=1.0, label="selected τ̄")
        ax.set_ylabel("forecast time τ [s]")
        ax.set_title(label)
        ax.legend(loc="upper right")
        fig.colorbar(image, ax=ax)
    for record, name in ((adj, "ADJ"), (constant, "const:0.5")):
        present = record.present[:, 0]
        axes[2].plot(record.times[present], 3.6 * record.speed[present, 0], label=name)
    axes[2].set_xlabel("time [s]")
    axes[2].set_ylabel(f"speed of {ego} [km/h]")
    axes[2].legend()
    fig.savefig(out, dpi=120)
    print(f"wrote {out}")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "roundabout-map.png")
