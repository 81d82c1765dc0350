"""`fsi plot DIR` for a flight (`fsi fly FLIGHT.yaml --out DIR`): the 3D path, the ground track with the
waypoints, the target and the wind, the flight's history (altitude, speeds, angles with the glide angle and the
glide path asked for, brakes and incidence) and, after a Monte Carlo, the landing scatter. Imported by
fsi_plot.py (which owns the index of the pictures and the lazy import of matplotlib)."""
import csv
import json
import os


def _summary(run_dir):
    path = os.path.join(run_dir, "summary.json")
    if not os.path.isfile(path):
        return {}
    with open(path) as f:
        return json.load(f)


def _wind_arrow(ax, np, wind, x0, y0, span, label=True):
    if not wind or not (wind[0] or wind[1]):
        return
    speed = np.hypot(wind[0], wind[1])
    ax.annotate("", xy=(x0 + 0.15 * span * wind[1] / speed, y0 + 0.15 * span * wind[0] / speed), xytext=(x0, y0),
                arrowprops=dict(arrowstyle="->", color="c", lw=2))
    if label:
        ax.plot([], [], "c-", lw=2, label=f"wind {speed:.1f} m/s (blows along the arrow)")


def _path(fig_index, plt, t, north, east, alt, title):
    fig = plt.figure(figsize=(7, 6))
    ax = fig.add_subplot(111, projection="3d")
    ax.plot(east, north, alt, "b-", lw=1.2, label="path")
    ax.plot(east, north, 0 * alt, color="0.6", lw=0.8, label="ground track")
    ax.scatter([east[0]], [north[0]], [alt[0]], color="g", label="start")
    ax.scatter([east[-1]], [north[-1]], [alt[-1]], color="r", label="end")
    ax.set_xlabel("east [m]")
    ax.set_ylabel("north [m]")
    ax.set_zlabel("altitude [m]")
    ax.set_title(f"{title}: flight path")
    ax.legend(loc="upper left")
    fig_index.save(fig, "flight_path.png", "flight path (3D)", [("path", len(t))])


def _track(fig_index, plt, np, north, east, summary, title):
    fig, ax = plt.subplots(figsize=(6.5, 6))
    ax.plot(east, north, "b-", label="ground track")
    ax.plot(east[0], north[0], "go", label="start")
    ax.plot(east[-1], north[-1], "rs", label="landing" if summary.get("landed") else "end")
    waypoints = summary.get("waypoints_ne_m", [])
    for i, w in enumerate(waypoints):
        ax.plot(w[1], w[0], "k^", label="waypoints" if i == 0 else None)
    if waypoints:
        ax.plot(waypoints[-1][1], waypoints[-1][0], "k*", ms=14, label=f"target (miss {summary['miss_distance_m']:.1f} m)")
    span = max(np.ptp(east), np.ptp(north), 1.0)
    _wind_arrow(ax, np, summary.get("wind_steady_ned_m_s"), east[0], north[0], span)
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("east [m]")
    ax.set_ylabel("north [m]")
    ax.set_title(f"{title}: ground track")
    ax.legend(fontsize=8)
    fig_index.save(fig, "ground_track.png", "ground track", [("track", len(north))])


def _history(fig_index, plt, np, data, title):
    t = data["time_s"]
    names = data.dtype.names
    fig, axes = plt.subplots(4, 1, figsize=(8, 10), sharex=True)
    axes[0].plot(t, data["altitude_m"], "k-")
    axes[0].set_ylabel("altitude [m]")
    axes[1].plot(t, data["airspeed_m_s"], "b-", label="airspeed")
    axes[1].plot(t, data["ground_speed_m_s"], "g-", label="ground speed")
    axes[1].plot(t, data["descent_rate_m_s"], "r-", label="descent rate")
    axes[1].set_ylabel("[m/s]")
    axes[1].legend(ncol=3)
    glide = np.degrees(np.arctan2(data["descent_rate_m_s"], np.maximum(data["ground_speed_m_s"], 1e-9)))
    axes[2].plot(t, data["roll_deg"], label="roll")
    axes[2].plot(t, data["pitch_deg"], label="pitch")
    axes[2].plot(t, data["alpha_deg"], label="angle of attack")
    axes[2].plot(t, glide, label="glide angle over ground")
    if "required_glide_deg" in names and np.any(data["required_glide_deg"] != 0):
        axes[2].plot(t, np.minimum(data["required_glide_deg"], 60), "k--", lw=0.8, label="glide path asked (<= 60)")
    axes[2].set_ylabel("[deg]")
    axes[2].legend(ncol=3, fontsize=8)
    axes[3].plot(t, data["brake_left"], label="left brake")
    axes[3].plot(t, data["brake_right"], "--", label="right brake")
    axes[3].set_ylabel("brake [0-1]")
    axes[3].set_xlabel("time [s]")
    if "incidence_deg" in names and np.any(data["incidence_deg"] != 0):
        ax2 = axes[3].twinx()
        ax2.plot(t, data["incidence_deg"], "m-", lw=1, label="incidence")
        ax2.set_ylabel("incidence [deg]", color="m")
        ax2.legend(loc="upper right")
    axes[3].legend(loc="upper left")
    axes[0].set_title(f"{title}: flight history")
    fig.tight_layout()
    fig_index.save(fig, "flight_history.png", "altitude, speeds, angles, brakes, incidence", [("rows", len(t))])


def _scatter(fig_index, plt, np, run_dir, summary, title):
    with open(os.path.join(run_dir, "monte_carlo.csv")) as f:
        rows = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]
    mc = summary.get("monte_carlo", {})
    north = np.array([r["landing_north_m"] for r in rows])
    east = np.array([r["landing_east_m"] for r in rows])
    speed = np.array([r["wind_speed_m_s"] for r in rows])
    fig, ax = plt.subplots(figsize=(6.5, 6))
    sc = ax.scatter(east, north, c=speed, cmap="viridis", s=18, label=f"landings ({len(rows)} runs, seed {mc.get('seed')})")
    fig.colorbar(sc, ax=ax, label="wind speed [m/s]")
    ax.plot(np.mean(east), np.mean(north), "r+", ms=14, mew=2, label="mean landing")
    target = summary.get("target_ne_m")
    if target:
        ax.plot(target[1], target[0], "k*", ms=14, label="target")
        for key, style, name in (("miss_median_m", "k--", "50 %"), ("miss_95_m", "k:", "95 %")):
            if key in mc:
                a = np.linspace(0, 2 * np.pi, 200)
                ax.plot(target[1] + mc[key] * np.sin(a), target[0] + mc[key] * np.cos(a), style, lw=0.8,
                        label=f"{name} of the misses: {mc[key]:.1f} m")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("east [m]")
    ax.set_ylabel("north [m]")
    ax.set_title(f"{title}: landing scatter")
    ax.legend(fontsize=8)
    fig_index.save(fig, "landing_scatter.png", "landing points of the Monte Carlo", [("runs", len(rows))])


def plot_flight(run_dir, out_dir, Index, plt, np, InputError):
    """The pictures of a flight; returns the index of what was written."""
    index = Index("flight", run_dir, out_dir)
    path = os.path.join(run_dir, "trajectory.csv")
    data = np.genfromtxt(path, delimiter=",", names=True)
    if data.size < 2:
        raise InputError(f"{path}: fewer than two rows")
    summary = _summary(run_dir)
    title = os.path.basename(summary.get("flight_file", run_dir))
    north, east, alt = data["north_m"], data["east_m"], data["altitude_m"]
    _path(index, plt, data["time_s"], north, east, alt, title)
    _track(index, plt, np, north, east, summary, title)
    _history(index, plt, np, data, title)
    if os.path.isfile(os.path.join(run_dir, "monte_carlo.csv")):
        _scatter(index, plt, np, run_dir, summary, title)
    return index
