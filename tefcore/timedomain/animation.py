"""Watch it flutter: the blade section, a side view of the blade and the work, animated.

:func:`animate` draws a :class:`~tefcore.timedomain.simulate.SimulationResult`
in four panels:

* **the section at the flap midspan**, to scale: a NACA 0012 outline of the
  configuration's chord with the flap (chord ratio ``E``) turning about its
  hinge (``o E`` behind the flap nose), the section plunging (flap bending at
  the midspan) and pitching (twist) about the elastic axis; the trim position
  in grey;
* **a side view of the blade** from the root to the tip: the elastic axis
  (flap bending) and the leading and trailing edges (twist), the flap's
  trailing edge over its span;
* **the amplitude** of the dominant component on a log scale, with the fitted
  growth and the Floquet real part as lines;
* **the work per revolution** of the mechanism's largest named terms
  (:mod:`tefcore.timedomain.work`) with the Floquet decomposition as ticks,
  and their sum against the energy growth.

The motion is normalised: one gain for all components keeps their true
ratios (largest angle 20 deg or plunge a quarter chord), each cycle is shown
over its own amplitude, and the growth is slowed to a factor
:data:`SHOWN_GROWTH` over the clip -- the true factor per revolution is in
the title and the amplitude panel shows the true scale.  The first
:data:`ANIMATED_REVS` revolutions (at most
:data:`~tefcore.timedomain.limits.MAX_ANIMATED_REVS`) are animated at :data:`FRAMES_PER_CYCLE`
frames per cycle of the root.  Frames are deterministic (same input, same
bytes).
"""

from __future__ import annotations

import math
import shutil
import textwrap

import numpy as np

from .limits import MAX_ANIMATED_REVS, check_bounded

__all__ = ["ANIMATED_REVS", "FRAMES_PER_CYCLE", "SHOWN_GROWTH", "animate", "check_writer",
           "gif_bytes", "naca0012", "render_frames", "save_animation"]

#: The displayed amplitude changes by this factor over the clip (growing or decaying).
SHOWN_GROWTH = 4.0
#: Largest displayed angle [deg] and plunge [chords].
SHOWN_ANGLE_DEG, SHOWN_PLUNGE = 20.0, 0.25
#: Frames per oscillation cycle of the root (by default).
FRAMES_PER_CYCLE = 8
#: Revolutions animated by default (the amplitude panel shows the whole march).
ANIMATED_REVS = 2
#: Terms shown in the work panel.
WORK_TERMS = 5


def naca0012(n: int = 60):
    """Upper surface of a NACA 0012 section, chord 1.

    Parameters
    ----------
    n : int, optional
        Points (cosine spacing).

    Returns
    -------
    x, y : numpy.ndarray
        Chordwise position from the leading edge and half thickness.
    """
    x = 0.5 * (1 - np.cos(np.linspace(0, np.pi, n)))
    y = 0.6 * (0.2969 * np.sqrt(x) - 0.1260 * x - 0.3516 * x**2 + 0.2843 * x**3 - 0.1036 * x**4)
    return x, y


def _section_shapes(cfg):
    """Main body and flap outlines (chord units, LE at 0), hinge, elastic axis."""
    e, o = cfg.flap.chord_ratio, cfg.flap.overhang
    nose, hinge = 1.0 - e, 1.0 - e + o * e
    x, y = naca0012(80)
    main = x <= nose
    body = np.r_[x[main], nose, nose, x[main][::-1]], np.r_[y[main], y[main][-1],
                                                            -y[main][-1], -y[main][::-1]]
    flap_x = x[x >= nose]
    yf = np.interp(flap_x, x, y)
    flap = np.r_[flap_x, flap_x[::-1]], np.r_[yf, -yf[::-1]]
    return body, flap, hinge, cfg.rotor.elastic_axis


def _rotate(xy, angle, about):
    """Rotate points (x, y) by ``angle`` (nose up positive: trailing edge down) about a point."""
    x, y = xy[0] - about[0], xy[1] - about[1]
    c, s = math.cos(angle), math.sin(angle)
    return x * c + y * s + about[0], -x * s + y * c + about[1]


def _display(result, psi):
    """Displayed components: over their local amplitude, growth slowed (:func:`_slowed`), one gain.

    Returns the components (rows of COMPONENTS, SI) times the display factor,
    and the caption of the normalisation.
    """
    n = result.stability.system.n_dof
    factor, rate = _slowed(result, psi)
    comp = (result.physical @ result.run.at(psi)[:n]) * factor[None, :]
    chord = result.stability.trim_result.model.cfg.rotor.chord
    angles = np.abs(comp[1:3]).max()
    gain = min(np.deg2rad(SHOWN_ANGLE_DEG) / max(angles, 1e-300),
               SHOWN_PLUNGE * chord / max(np.abs(comp[3]).max(), 1e-300))
    true = math.exp(2 * math.pi * rate)
    caption = (f"motion over its amplitude in each cycle (one gain for all: true ratios), "
               f"growth shown as x{SHOWN_GROWTH if rate > 0 else 1 / SHOWN_GROWTH:g} over the "
               f"clip; true: x{true:.3g} per revolution (amplitude panel)")
    return comp * gain, caption, gain


def check_writer(path, fmt: str) -> None:
    """Refuse an animation format that cannot be written here, before computing.

    Parameters
    ----------
    path : str or os.PathLike
        The output file.
    fmt : {"gif", "mp4"}
        Its format.

    Raises
    ------
    ValueError
        ``mp4`` without ffmpeg on the PATH, or an unknown format.
    """
    if fmt == "mp4" and shutil.which("ffmpeg") is None:
        raise ValueError(f"--mp4 {path}: writing MP4 needs ffmpeg on the PATH, which is not "
                         "installed; use --gif, or install ffmpeg")
    if fmt not in ("gif", "mp4"):
        raise ValueError(f"{path}: unknown animation format {fmt!r} (gif or mp4)")


def _frames(result, frames_per_rev, revs):
    """Frame azimuths over the first ``revs`` revolutions (all: None), the last at the end.

    Default: :data:`FRAMES_PER_CYCLE` frames per cycle of the root's oscillation
    (at least 12 a revolution): fewer frames than that and a 10 /rev root shows
    as a slow stroboscopic wobble (found looking at 12 frames a revolution).
    """
    end = result.run.psi_end if revs is None else min(result.run.psi_end, 2 * np.pi * revs)
    check_bounded("revs", end / (2 * np.pi), MAX_ANIMATED_REVS,
                  "revolutions animated" + (": the whole march" if revs is None else ""))
    if frames_per_rev is None:
        freq = abs(result.summary["frequency_floquet_per_rev"])
        frames_per_rev = max(12, int(np.ceil(FRAMES_PER_CYCLE * freq)))
    count = max(2, int(round(frames_per_rev * end / (2 * np.pi))) + 1)
    return np.linspace(0.0, end, count)


def _draw_section(ax, cfg):
    """The section's artists: trim outline (grey), moving body and flap, hinge, axis."""
    body, flap, hinge, ea = _section_shapes(cfg)
    for shape in (body, flap):
        ax.plot(*shape, color="0.8", lw=1)
    b, = ax.fill(*body, color="C0", alpha=0.75, lw=1, ec="C0")
    f, = ax.fill(*flap, color="C3", alpha=0.8, lw=1, ec="C3")
    h, = ax.plot([hinge], [0.0], "ko", ms=4)
    a, = ax.plot([ea], [0.0], "k+", ms=9, mew=1.5)
    ax.set_xlim(-0.15, 1.15)
    ax.set_ylim(-0.45, 0.45)
    ax.set_aspect("equal")
    ax.set_xlabel("chord")
    ax.set_title(f"section at the flap midspan ({cfg.flap.midspan:.2f} R), to scale",
                 fontsize="small")
    return {"body": b, "flap": f, "hinge": h, "axis": a, "shapes": (body, flap, hinge, ea)}


def _update_section(art, plunge, pitch, delta):
    """Move the section: plunge (chords, up), pitch (nose up) about the axis, flap about hinge."""
    body, flap, hinge, ea = art["shapes"]
    flap_xy = _rotate(flap, -delta, (hinge, 0.0))       # trailing edge down
    parts = [_rotate(body, pitch, (ea, 0.0)), _rotate(flap_xy, pitch, (ea, 0.0)),
             _rotate((np.array([hinge]), np.zeros(1)), pitch, (ea, 0.0))]
    art["body"].set_xy(np.column_stack([parts[0][0], parts[0][1] + plunge]))
    art["flap"].set_xy(np.column_stack([parts[1][0], parts[1][1] + plunge]))
    art["hinge"].set_data(parts[2][0], parts[2][1] + plunge)
    art["axis"].set_data([ea], [plunge])


def _side_view(ax, model):
    """The side view's artists and the shapes they use (w in chords, twist)."""
    cfg = model.cfg
    x = np.linspace(cfg.rotor.root_offset, 1.0, 60)
    sh = model.modes.shapes(x)
    ax.axvspan(cfg.flap.midspan - cfg.flap.span / 2, cfg.flap.midspan + cfg.flap.span / 2,
               color="C3", alpha=0.12, lw=0, label="flap")
    lines = {k: ax.plot(x, 0 * x, color=c, lw=lw, label=lab)[0] for k, c, lw, lab in (
        ("le", "C0", 1.0, "leading edge"), ("axis", "k", 1.8, "elastic axis (bending)"),
        ("te", "C2", 1.0, "trailing edge"))}
    fx = x[(x >= cfg.flap.midspan - cfg.flap.span / 2) & (x <= cfg.flap.midspan
                                                           + cfg.flap.span / 2)]
    lines["flap"] = ax.plot(fx, 0 * fx, color="C3", lw=2, label="flap trailing edge")[0]
    ax.set_xlim(0, 1.02)
    ax.set_ylim(-1.0, 1.0)
    ax.set_xlabel("span r/R")
    ax.set_ylabel("displacement [chords, normalised]")
    ax.set_title("side view: bending and twist", fontsize="small")
    ax.legend(fontsize="x-small", loc="lower left", ncol=2)
    flap_sh = model.modes.shapes(fx)
    return lines, (sh, flap_sh)


def _amplitude_panel(ax, result):
    """Log amplitude of the fitted component, the fitted and the Floquet growth lines."""
    s = result.summary
    names = ("tip_flap_bending", "twist_flap_midspan", "flap_deflection", "plunge_flap_midspan")
    j = names.index(s["component"])
    end = result.run.psi_end
    psi = np.linspace(0.0, end, int(256 * end / (2 * np.pi)) + 1)
    comp = result.physical[j] @ result.run.at(psi)[:result.stability.system.n_dof]
    with np.errstate(divide="ignore"):
        logv = np.log10(np.abs(comp))
    start = logv[0] if np.isfinite(logv[0]) else np.nanmax(logv[:10])
    rev = psi / (2 * np.pi)
    for rate, style, label in ((s["growth_floquet_per_rev"], "k--", "Floquet"),
                               (s["growth_time_domain_per_rev"], "C1:", "fitted")):
        if rate is not None and math.isfinite(rate):
            ax.plot(rev, start + rate * psi / math.log(10), style, lw=1.2,
                    label=f"{label} {rate:+.3f} /rev")
    ax.plot(rev, logv, color="C0", lw=0.5, alpha=0.25)
    line, = ax.plot([], [], color="C0", lw=0.8, label=s["component"].replace("_", " "))
    finite = logv[np.isfinite(logv)]
    ax.set_xlim(0, rev[-1])
    ax.set_ylim(max(finite.min(), start - 25) - 1, finite.max() + 1)
    ax.set_xlabel("revolutions")
    ax.set_ylabel("log10 |amplitude|")
    ax.set_title("amplitude (true scale)", fontsize="small")
    ax.legend(fontsize="x-small", loc="best")
    return line, rev, logv


def _work_panel(ax, result):
    """Horizontal bars of the largest terms' work for one revolution, Floquet ticks."""
    work, fl = result.work, result.floquet_work
    if work is None or not len(work):
        ax.text(0.5, 0.5, "work not computed", ha="center", va="center", transform=ax.transAxes)
        ax.set_axis_off()
        return None
    terms = [c for c in work.columns if c not in ("revolution", "sum", "energy_growth")]
    ranked = sorted(terms, key=lambda t: -abs(fl.get(t, work[t].iloc[-1])))[:WORK_TERMS]
    y = np.arange(len(ranked))[::-1]
    bars = ax.barh(y, [work[t].iloc[0] for t in ranked], color="C0", alpha=0.8,
                   label="time domain, this revolution")
    ax.plot([fl.get(t, np.nan) for t in ranked], y, "k|", ms=14, mew=2,
            label="Floquet decomposition")
    ax.set_yticks(y, [textwrap.fill(t, 26) for t in ranked], fontsize="x-small")
    span = np.nanmax(np.abs(work[ranked].to_numpy())) * 1.15
    ax.set_xlim(-span, span)
    ax.axvline(0, color="k", lw=0.6)
    ax.set_xlabel("work / (2 × energy) per revolution [/rev]")
    ax.legend(fontsize="x-small", loc="lower right")
    return bars, ranked


def _scene(result, frames_per_rev, dpi, figsize, revs=ANIMATED_REVS):
    """The figure, its per-frame update, the artists that move, the frame count, and
    each frame's stage (the revolution of the work panel: drawn with the background)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    if revs is not None:                          # before the result is looked at
        check_bounded("revs", revs, MAX_ANIMATED_REVS, "revolutions animated")
    model = result.stability.trim_result.model
    cfg, chord, n, nm = model.cfg, model.cfg.rotor.chord, model.n_dof, model.n_modes
    frames = _frames(result, frames_per_rev, revs)
    comp, caption, gain = _display(result, frames)
    # about 12 characters of the title's font per inch: the caption wrapped to
    # the figure (one line of 170 characters was cut at both sides of an
    # 800-px page, seen in the explorer's headless check)
    caption = textwrap.fill(caption, max(40, int(12 * figsize[0])))
    fig = Figure(figsize=figsize, dpi=dpi, layout="constrained")
    FigureCanvasAgg(fig)
    axs = fig.subplots(2, 2)
    sec = _draw_section(axs[0, 0], cfg)
    side, (sh, flap_sh) = _side_view(axs[0, 1], model)
    amp_line, rev, logv = _amplitude_panel(axs[1, 0], result)
    work = _work_panel(axs[1, 1], result)
    states = result.run.at(frames)[:n] * (gain * _slowed(result, frames)[0])[None, :]
    ea = cfg.rotor.elastic_axis
    w = sh["w"] @ states[:nm] * cfg.rotor.radius / chord
    phi = sh["phi"] @ states[:nm]
    tef = (flap_sh["w"] @ states[:nm] * cfg.rotor.radius / chord
           - (1 - ea) * (flap_sh["phi"] @ states[:nm])
           - cfg.flap.chord_ratio * (states[nm] if model.has_flap else 0.0))
    top = max(np.abs(w + ea * phi).max(), np.abs(w - (1 - ea) * phi).max(), np.abs(tef).max())
    axs[0, 1].set_ylim(-1.15 * top, 1.15 * top)
    s = result.summary
    # the title and caption are still (drawn once, with the background); only
    # the azimuth moves, a short text of its own: drawn with the wrapped
    # caption in every frame, the text takes 13 of the 18.5 s notebook 11
    # spends on its two GIFs (measured, 167 frames each)
    fig.suptitle(f"{cfg.name}: {s['mode']} ({s['start']}), Floquet "
                 f"{s['growth_floquet_per_rev']:+.3f} /rev\n{caption}", fontsize="medium")
    clock = axs[0, 0].text(0.02, 0.97, " ", transform=axs[0, 0].transAxes, ha="left",
                           va="top", fontsize="small")
    # the work panel changes once a revolution: drawn with the background
    # (render_frames draws it anew when the revolution changes)
    moving = [sec["body"], sec["flap"], sec["hinge"], sec["axis"], *side.values(), amp_line,
              clock]

    def stage(i):
        """The revolution whose work the panel shows at frame ``i``."""
        return min(int(frames[i] // (2 * np.pi)), len(result.work) - 1) if work else 0

    def update(i):
        psi = frames[i]
        _update_section(sec, comp[3, i] / chord, comp[1, i], comp[2, i])
        side["axis"].set_ydata(w[:, i])
        side["le"].set_ydata(w[:, i] + ea * phi[:, i])
        side["te"].set_ydata(w[:, i] - (1 - ea) * phi[:, i])
        side["flap"].set_ydata(tef[:, i])
        upto = rev <= psi / (2 * np.pi) + 1e-12
        amp_line.set_data(rev[upto], logv[upto])
        if work:
            k = stage(i)
            for bar, t in zip(work[0], work[1], strict=True):
                bar.set_width(result.work[t].iloc[k])
            axs[1, 1].set_title(f"work over revolution {k + 1}: sum "
                                f"{result.work['sum'].iloc[k]:+.3f} = energy growth "
                                f"{result.work['energy_growth'].iloc[k]:+.3f} /rev",
                                fontsize="small")
        clock.set_text(f"psi = {psi / (2 * np.pi):.2f} rev")
        return moving

    update(0)
    return fig, update, moving, len(frames), stage


def animate(result, *, frames_per_rev: int | None = None, dpi: int = 72,
            figsize=(11.0, 7.0), revs: float | None = ANIMATED_REVS):
    """The animation of a simulation (four panels, see the module's description).

    Parameters
    ----------
    result : tefcore.timedomain.simulate.SimulationResult
        The simulation (with ``work`` for the work panel).
    frames_per_rev : int, optional
        Frames per revolution (default: :data:`FRAMES_PER_CYCLE` per cycle of
        the root, at least 12).
    dpi : int, optional
        Resolution of the frames.
    figsize : tuple of float, optional
        Figure size [in].
    revs : float or None, optional
        Revolutions animated (None: the whole march); the amplitude panel
        shows the whole march.

    Returns
    -------
    matplotlib.animation.FuncAnimation
        For a live figure or ``to_jshtml``; files are written faster by
        :func:`save_animation` (the same frames, blitted).
    """
    import matplotlib.animation

    fig, update, _, count, _ = _scene(result, frames_per_rev, dpi, figsize, revs)
    return matplotlib.animation.FuncAnimation(fig, update, frames=count, interval=80,
                                              repeat=True)


def render_frames(result, *, frames_per_rev: int | None = None, dpi: int = 72,
                  figsize=(11.0, 7.0), revs: float | None = ANIMATED_REVS):
    """The frames of :func:`animate` as images: the still parts drawn once, the moving blitted.

    Parameters
    ----------
    result : tefcore.timedomain.simulate.SimulationResult
        The simulation.
    frames_per_rev : int, optional
        Frames per revolution (default: :data:`FRAMES_PER_CYCLE` per cycle of
        the root, at least 12).
    dpi : int, optional
        Resolution.
    figsize : tuple of float, optional
        Figure size [in].
    revs : float or None, optional
        Revolutions animated (None: the whole march); the amplitude panel
        shows the whole march.

    Returns
    -------
    list of PIL.Image.Image
        RGB frames.
    """
    from PIL import Image

    fig, update, moving, count, stage = _scene(result, frames_per_rev, dpi, figsize, revs)
    canvas = fig.canvas
    canvas.draw()                    # the layout, with the first frame's text
    fig.set_layout_engine("none")    # frozen: the moving artists keep their places
    for a in moving:
        a.set_animated(True)
    images, shown, background = [], None, None
    for i in range(count):
        if stage(i) != shown:        # a new revolution's work: a new background
            update(i)
            canvas.draw()
            background, shown = canvas.copy_from_bbox(fig.bbox), stage(i)
        canvas.restore_region(background)
        update(i)
        for a in moving:
            fig.draw_artist(a)
        images.append(Image.frombuffer("RGBA", canvas.get_width_height(),
                                       bytes(canvas.buffer_rgba())).convert("RGB"))
    return images


def _slowed(result, psi):
    """Display factor at ``psi``: the motion over its amplitude in the surrounding cycle,
    times a growth of :data:`SHOWN_GROWTH` over the clip; and the true rate.

    The true response is no smooth exponential: at mu = 0.3 the flutter root
    grows in bursts, its periodic shape varying a thousandfold within the
    revolution (the amplitude panel shows it), so a display scaled by the
    fitted exponential alone is still for most frames (found looking at the
    frames).  Divided by its local amplitude -- the largest kinematic
    displacement within half an oscillation period either side -- the motion
    shows its shape and phase in every frame; the growth is then shown by the
    slowed factor, and in true scale in the amplitude panel.
    """
    s = result.summary
    rate = s["growth_time_domain_per_rev"]
    if rate is None or not math.isfinite(rate):
        rate = s["growth_floquet_per_rev"]
    span = max(psi[-1] - psi[0], 1e-12)
    shown = (math.copysign(math.log(SHOWN_GROWTH) / span, rate) if abs(rate) > 0.005 else 0.0)
    model = result.stability.trim_result.model
    cfg, n = model.cfg, model.n_dof
    weights = np.array([1.0, 0.5 * cfg.rotor.chord, cfg.flap.chord_ratio * cfg.rotor.chord,
                        1.0])
    fine = np.linspace(0.0, result.run.psi_end, int(256 * result.run.psi_end / (2 * np.pi)) + 2)
    kin = np.max(np.abs(result.physical @ result.run.at(fine)[:n]) * weights[:, None], axis=0)
    half = np.pi / max(abs(s["frequency_floquet_per_rev"]), 0.5)
    local = np.array([kin[(fine >= p - half) & (fine <= p + half)].max() for p in psi])
    return np.exp(shown * (psi - psi[-1])) / np.where(local > 0, local, 1.0), rate


def _palette():
    """A fixed GIF palette: matplotlib's ten colours blended with white, and greys.

    One palette for every frame, without dithering: the frames of a line
    drawing then compress five times better than with a palette of their own
    (measured: 49 kB against 213 kB for 21 frames), keep their colours, and
    are the same bytes on every run.
    """
    from matplotlib import colors
    from PIL import Image

    entries = [tuple(round(255 * (t * c + 1 - t)) for c in colors.to_rgb(f"C{i}"))
               for i in range(10) for t in np.linspace(0.0, 1.0, 10)]
    entries += [(round(g),) * 3 for g in np.linspace(0, 255, 40)]
    flat = [v for rgb in entries for v in rgb]
    palette = Image.new("P", (1, 1))
    palette.putpalette(flat + [255] * (768 - len(flat)))
    return palette


def _gif(images, fps) -> bytes:
    """GIF bytes of RGB frames (Pillow, as matplotlib's PillowWriter; looping)."""
    import io

    from PIL import Image

    palette = _palette()
    frames = [im.quantize(palette=palette, dither=Image.Dither.NONE) for im in images]
    buf = io.BytesIO()
    frames[0].save(buf, format="GIF", save_all=True, append_images=frames[1:],
                   duration=int(round(1000 / fps)), loop=0)
    return buf.getvalue()


def _mp4(images, fps) -> bytes:
    """MP4 (H.264) bytes of RGB frames through ffmpeg."""
    import os
    import subprocess
    import tempfile

    w, h = images[0].size
    with tempfile.TemporaryDirectory(prefix="tefcore-anim-") as tmp:
        out = os.path.join(tmp, "animation.mp4")
        cmd = ["ffmpeg", "-loglevel", "error", "-y", "-f", "rawvideo", "-pix_fmt", "rgb24",
               "-s", f"{w}x{h}", "-r", str(fps), "-i", "-", "-vf",
               "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-pix_fmt", "yuv420p", "-c:v", "libx264",
               "-fflags", "+bitexact", "-flags:v", "+bitexact", out]
        proc = subprocess.run(cmd, input=b"".join(im.tobytes() for im in images),
                              capture_output=True, check=False)
        if proc.returncode:
            raise ValueError("ffmpeg failed: " + proc.stderr.decode(errors="replace")[-300:])
        with open(out, "rb") as f:
            return f.read()


def save_animation(result, path, fmt: str, *, fps: int = 12, frames_per_rev: int | None = None,
                   dpi: int = 72, revs: float | None = ANIMATED_REVS) -> None:
    """Write the animation of a simulation atomically: GIF (Pillow) or MP4 (ffmpeg).

    Parameters
    ----------
    result : tefcore.timedomain.simulate.SimulationResult
        The simulation.
    path : str or os.PathLike
        The output file (check it beforehand with :func:`check_writer`).
    fmt : {"gif", "mp4"}
        The format.
    fps : int, optional
        Frames per second.
    frames_per_rev : int, optional
        Frames per revolution (default: :data:`FRAMES_PER_CYCLE` per cycle of
        the root, at least 12).
    dpi : int, optional
        Resolution.
    revs : float or None, optional
        Revolutions animated (None: the whole march).
    """
    from ..safe_io import atomic_write_bytes

    check_writer(path, fmt)
    images = render_frames(result, frames_per_rev=frames_per_rev, dpi=dpi, revs=revs)
    data = _gif(images, fps) if fmt == "gif" else _mp4(images, fps)
    atomic_write_bytes(path, data, what=f"--{fmt}")


def gif_bytes(result, *, fps: int = 12, frames_per_rev: int | None = None, dpi: int = 72,
              figsize=(11.0, 7.0), revs: float | None = ANIMATED_REVS) -> bytes:
    """The animation as GIF bytes (to embed in a page or notebook as an ``<img>``).

    Parameters
    ----------
    result : tefcore.timedomain.simulate.SimulationResult
        The simulation.
    fps : int, optional
        Frames per second.
    frames_per_rev : int, optional
        Frames per revolution (default: :data:`FRAMES_PER_CYCLE` per cycle of
        the root, at least 12).
    dpi : int, optional
        Resolution.
    figsize : tuple of float, optional
        Figure size [in].
    revs : float or None, optional
        Revolutions animated (None: the whole march); the amplitude panel
        shows the whole march.

    Returns
    -------
    bytes
    """
    return _gif(render_frames(result, frames_per_rev=frames_per_rev, dpi=dpi, figsize=figsize,
                              revs=revs), fps)
