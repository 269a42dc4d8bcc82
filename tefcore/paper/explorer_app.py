"""The explorer as a web page: sliders, root map, the flutter root's mechanism, an animation.

``tefcore explore`` serves :func:`page` with voila (the optional extra
``tefcore[app]``): a page with the four sliders of
:mod:`tefcore.paper.explorer` (flap CG offset, overhang, actuator stiffness,
advance ratio).  Releasing a slider recomputes the point and redraws

* the **root map** (:func:`tefcore.paper.explorer.draw_root_map`: every
  Floquet root, the TEF root and the flutter root, the grey trail of the
  previous states),
* the **mechanism bars** of the flutter root (the least stable flap-induced
  root): the work of each named term over twice the mode's energy
  (:func:`tefcore.linear.mechanism.mechanism`), which adds up to its real part;

and the button *animate the flutter root* marches it for two revolutions
(:func:`tefcore.timedomain.simulate.simulate`) and shows the animation
(:mod:`tefcore.timedomain.animation`) as a GIF.  Figures are PNG images that
scale with the page, so the layout holds from a lecture-hall projector to a
laptop: the controls and figures wrap below each other on narrow screens.

The page-building functions run without a browser or voila
(``tests/paper/test_explorer_app.py``); ``tools/check_explorer.py`` drives the
served page in headless Chromium.

Examples
--------
>>> names, values = mechanism_bars({"a": 0.5, "b": -0.1, "c": 1e-9}, top=2)
>>> names, values
(['a', 'b'], [0.5, -0.1])
"""

from __future__ import annotations

import io
import json
import re
import textwrap

from ..errors import TefcoreError
from .explorer import SLIDERS, RootMap, draw_root_map, explorer_config, explorer_state

__all__ = ["ANIMATION_REVS", "FIGURE_DPI", "MissingExtra", "PageState", "check_port",
           "check_voila", "figure_png", "free_port", "mechanism_bars", "mechanism_figure",
           "notebook_json", "page", "page_state", "serve"]

#: Revolutions of the animation on request (short: about 10 s on two cores).
ANIMATION_REVS = 2
#: Resolution of the page's figures (they scale with the page).
FIGURE_DPI = 90
#: JupyterLab extensions the page does not load (editors' extensions, not a page's).
VOILA_DENIED = ("jupyterlab-jupytext",)
#: Terms shown in the mechanism bars.
BAR_TERMS = 7


def figure_png(fig) -> bytes:
    """A matplotlib figure as PNG bytes (deterministic: no metadata).

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure.

    Returns
    -------
    bytes
    """
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=FIGURE_DPI, metadata={"Software": None})
    return buf.getvalue()


def mechanism_bars(contributions: dict, top: int = BAR_TERMS):
    """The terms to draw: the ``top`` largest contributions by magnitude.

    Parameters
    ----------
    contributions : dict of str to float
        Term -> contribution to the root's real part [/rev].
    top : int, optional
        How many.

    Returns
    -------
    names : list of str
    values : list of float
    """
    ranked = sorted(contributions.items(), key=lambda kv: -abs(kv[1]))[:top]
    ranked = [(k, v) for k, v in ranked if abs(v) > 1e-6] or ranked[:1]
    return [k for k, _ in ranked], [float(v) for _, v in ranked]


def mechanism_figure(contributions: dict, total: float | None, label: str):
    """The mechanism bars of one root as a figure.

    Parameters
    ----------
    contributions : dict of str to float
        Term -> contribution to the real part [/rev]; empty: nothing to show.
    total : float or None
        The root's real part (the sum of all contributions).
    label : str
        What the root is, for the title (or why there are no bars).

    Returns
    -------
    matplotlib.figure.Figure
    """
    from matplotlib.figure import Figure

    fig = Figure(figsize=(11.5, 4.0), layout="constrained")
    ax = fig.subplots()
    if not contributions:
        ax.text(0.5, 0.5, "\n".join(textwrap.wrap(label, 50)), ha="center", va="center",
                transform=ax.transAxes, fontsize="small")
        ax.set_axis_off()
        return fig
    names, values = mechanism_bars(contributions)
    colors = ["C3" if v > 0 else "C0" for v in values]
    ax.barh([textwrap.fill(n, 34) for n in names][::-1], values[::-1], color=colors[::-1])
    ax.axvline(0, color="k", lw=0.8)
    ax.tick_params(axis="y", labelsize="medium")
    ax.set_xlabel("work / (2 × energy) [/rev]   (> 0 destabilising)")
    ax.set_title(f"mechanism of the {label}" + (f": real part {total:+.3f} /rev"
                                                 if total is not None else ""),
                 fontsize="medium")
    return fig


class PageState:
    """What the page shows for one set of slider values.

    Parameters
    ----------
    roots : RootMap
        The roots (:func:`tefcore.paper.explorer.explorer_state`).
    contributions : dict
        The flutter root's mechanism (term -> contribution [/rev]); empty when
        there is no flutter root or no roots.
    label : str
        The flutter root's description (or why there is none).
    total : float or None
        Its real part [/rev].
    stability : object
        The point's :class:`~tefcore.linear.stability.StabilityResult` (for
        the animation), or None.
    """

    def __init__(self, roots: RootMap, contributions: dict, label: str, total, stability):
        self.roots, self.contributions, self.label = roots, contributions, label
        self.total, self.stability = total, stability


def page_state(base=None, **values) -> PageState:
    """Compute one state of the page: the roots and the flutter root's mechanism.

    Parameters
    ----------
    base : tefcore.config.configuration.Config, optional
        Base configuration (default: MDART, thin-airfoil aerodynamics).
    **values
        The slider values (:data:`tefcore.paper.explorer.SLIDERS`).

    Returns
    -------
    PageState
    """
    from ..linear.mechanism import mechanism
    from ..linear.stability import stability

    try:
        cfg = explorer_config(base, **values)
        res = stability(cfg)
    except (TefcoreError, ValueError) as exc:
        return PageState(explorer_state(base, **values), {}, f"no roots: {exc}", None, None)
    from ..modes.roles import flutter_root

    tef = res.modes[res.modes["label"] == "TEF"]
    roots = RootMap(res.modes, complex(tef["real_part"].iloc[0], tef["frequency_per_rev"].iloc[0])
                    if len(tef) else None, flutter_root(res.modes))
    if roots.flutter is None:
        return PageState(roots, {}, "no flap-induced root", None, res)
    mech = mechanism(cfg, mode="flutter", knockouts=False, stability_result=res)
    terms = mech.table[~mech.table["term"].str.startswith(("total", "knockout"))]
    label = f"flutter root (from {mech.label})"
    return PageState(roots, dict(zip(terms["term"], terms["contribution_real"], strict=True)),
                     label, float(mech.eigenvalue.real), res)


def notebook_json(config: str = "mdart", overrides: list[str] | None = None,
                  folder: str | None = None) -> str:
    """The one-cell notebook that voila serves: :func:`page` of the configuration.

    Parameters
    ----------
    config : str, optional
        Configuration file or packaged name.
    overrides : list of str, optional
        ``NAME=VALUE`` overrides (the command's ``--set``).
    folder : str, optional
        The folder relative paths are read from (the command's): the kernel
        starts there, not in the notebook's temporary folder.

    Returns
    -------
    str
        The notebook (nbformat 4, JSON).
    """
    source = ("from tefcore.paper.explorer_app import page\n"
              f"_page = page(config={config!r}, overrides={list(overrides or [])!r})")
    if folder is not None:
        source = f"import os\nos.chdir({str(folder)!r})\n" + source
    nb = {"cells": [{"cell_type": "code", "execution_count": None, "id": "explorer",
                     "metadata": {}, "outputs": [], "source": source}],
          "metadata": {"kernelspec": {"display_name": "Python 3", "language": "python",
                                      "name": "python3"},
                       "language_info": {"name": "python"}},
          "nbformat": 4, "nbformat_minor": 5}
    return json.dumps(nb, indent=1)


def _sliders(widgets):
    """The four sliders of the explorer, released-value updates only."""
    return {k: widgets.FloatSlider(value=default, min=lo, max=hi, step=step,
                                   continuous_update=False, readout_format=".2f",
                                   layout=widgets.Layout(width="100%", max_width="460px"))
            for k, (_, lo, hi, step, default) in SLIDERS.items()}


_HELP = """<p style="font-size: small; line-height: 1.35">Release a slider to recompute the
point (a few seconds). <b>Root map</b>: every Floquet root, coloured by how much the flap takes
part; the red circle is the TEF root, the cross the flutter root (the least stable
flap-induced root); grey dots are the previous states. <b>Mechanism</b>: the work of each
named term on the flutter root over twice its energy; the bars add up to its real part
(red destabilises). <b>Animate</b>: the flutter root marched for two revolutions
(motion normalised; growth slowed and stated).</p>"""


def _title(values: dict) -> str:
    return (f"c_cg/c_f = {values['cg_offset']:.2f}, c_b/c_f = {values['overhang']:.2f}, "
            f"actuator × {values['actuator_scale']:.2f}, μ = {values['advance_ratio']:.2f}")


def _root_png(state: PageState, trail, title: str) -> bytes:
    from matplotlib.figure import Figure

    fig = Figure(figsize=(11.5, 4.6), layout="constrained")
    return figure_png(draw_root_map(fig, state.roots, trail, title))


def _controls(widgets):
    """The page's widgets by name: sliders, figures, button, animation, status."""
    w = {"sliders": _sliders(widgets),
         "status": widgets.HTML(value="", layout=widgets.Layout(min_height="1.6em")),
         # no icon: ipywidgets would fetch Font Awesome from a CDN, which an offline
         # lecture hall does not reach (a console error, found by tools/check_explorer.py)
         "animate": widgets.Button(description="▶ animate the flutter root",
                                   layout=widgets.Layout(width="auto")),
         # hidden until it has a frame: an empty image shows as a broken one
         "animation": widgets.Image(format="gif", layout=widgets.Layout(
             width="100%", height="auto", max_width="800px", display="none"))}
    for k in ("roots", "mechanism"):
        w[k] = widgets.Image(format="png", layout=widgets.Layout(width="100%", height="auto"))
    return w


def _layout(widgets, w):
    """Controls beside the figures, wrapping below each other on a narrow page."""
    labelled = [widgets.VBox([widgets.Label(SLIDERS[k][0]), s],
                             layout=widgets.Layout(margin="0 0 6px 0"))
                for k, s in w["sliders"].items()]
    controls = widgets.VBox([widgets.HTML("<h3>tefcore explorer: a rotor blade with a "
                                          "trailing-edge flap</h3>"), *labelled,
                             w["animate"], w["status"], widgets.HTML(_HELP)],
                            layout=widgets.Layout(flex="1 1 360px", max_width="480px"))
    figures = widgets.VBox([w["roots"], w["mechanism"]],
                           layout=widgets.Layout(flex="3 1 520px", min_width="0"))
    wrap = widgets.Layout(display="flex", flex_flow="row wrap", align_items="flex-start",
                          width="100%")
    return widgets.VBox([widgets.Box([controls, figures], layout=wrap), w["animation"]],
                        layout=widgets.Layout(width="100%"))


def _page_base(config, overrides):
    from ..config.io import load_config
    from ..config.text_input import parse_overrides
    from .figures.runs import base_config

    if config == "mdart" and not overrides:
        return base_config()
    base = load_config(config)
    return base.with_overrides(parse_overrides(overrides)) if overrides else base


def page(config: str = "mdart", overrides: list[str] | None = None, *, display: bool = True):
    """Build the page (and display it): sliders, root map, mechanism bars, animation button.

    Parameters
    ----------
    config : str, optional
        Configuration file or packaged name (the sliders override it).
    overrides : list of str, optional
        ``NAME=VALUE`` overrides, units as on the command line.
    display : bool, optional
        Display the page (in a notebook or voila); False only builds it.

    Returns
    -------
    ipywidgets.VBox
        The page; ``.children`` hold the controls and the figures, and
        ``page.tefcore`` the widgets by name (``sliders``, ``roots``,
        ``mechanism``, ``animate``, ``animation``, ``status``) and the
        callbacks ``redraw`` and ``run_animation``.
    """
    import ipywidgets as widgets

    base = _page_base(config, overrides)
    w = _controls(widgets)
    status, trail, current = w["status"], [], {}

    def redraw(_change=None):
        now = {k: s.value for k, s in w["sliders"].items()}
        status.value = "<i>computing the roots and the flutter root's mechanism …</i>"
        state = page_state(base, **now)
        w["roots"].value = _root_png(state, trail[-12:], _title(now))
        w["mechanism"].value = figure_png(mechanism_figure(state.contributions, state.total,
                                                           state.label))
        trail.append(state.roots)
        current.update(state=state, values=now)
        w["animate"].disabled = state.stability is None or state.roots.flutter is None
        status.value = "" if state.roots.error == "" else f"<b>{state.roots.error}</b>"

    def run_animation(_button=None):
        state = current.get("state")
        if state is None or state.stability is None:
            return
        from ..timedomain.animation import gif_bytes
        from ..timedomain.simulate import simulate

        status.value = "<i>marching the flutter root for two revolutions …</i>"
        sim = simulate(state.stability.trim_result.model.cfg, "flutter", revs=ANIMATION_REVS,
                       stability_result=state.stability)
        w["animation"].value = gif_bytes(sim, dpi=80, figsize=(10.0, 6.4))
        w["animation"].layout.display = "block"
        s = sim.summary
        status.value = (f"{s['mode']}: growth {s['growth_time_domain_per_rev']:+.3f} /rev "
                        f"marched, {s['growth_floquet_per_rev']:+.3f} /rev Floquet")

    for s in w["sliders"].values():
        s.observe(redraw, names="value")
    w["animate"].on_click(run_animation)
    box = _layout(widgets, w)
    box.tefcore = {**w, "redraw": redraw, "run_animation": run_animation}
    redraw()
    if display:
        from IPython.display import display as show

        show(box)
    return box


class MissingExtra(TefcoreError, ImportError):
    """An optional dependency (an extra of tefcore) is not installed."""


def check_voila() -> None:
    """Raise :class:`MissingExtra` unless voila is importable.

    Raises
    ------
    MissingExtra
        With the command that installs it.
    """
    import importlib.util

    if importlib.util.find_spec("voila") is None:
        raise MissingExtra("tefcore explore serves the page with voila, which is not "
                           "installed: pip install 'tefcore[app]' (or pip install voila)")


def free_port() -> int:
    """A free TCP port on the loopback interface.

    Returns
    -------
    int
    """
    import socket

    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def check_port(port: int) -> int:
    """The port to serve on: `port` when it is free on 127.0.0.1, a free one for 0.

    Bound as the server binds it (``SO_REUSEADDR``: a port a closed connection
    left waiting is free), and closed again at once.

    Parameters
    ----------
    port : int
        0 to 65535 (0: any free port).

    Returns
    -------
    int

    Raises
    ------
    ValueError
        Out of range, or in use (naming it).
    """
    import socket

    if not 0 <= port <= 65535:
        raise ValueError(f"--port {port}: must be a TCP port in [1, 65535] (0: any free port)")
    if port == 0:
        return free_port()
    with socket.socket() as s:
        s.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        try:
            s.bind(("127.0.0.1", port))
        except OSError as err:
            raise ValueError(f"--port {port}: cannot serve on it ({err.strerror}): another "
                             "program has it; choose another port, or --port 0 for a free "
                             "one") from None
    return port


#: A log record of voila, Jupyter or the kernel at WARNING level (``[Voila] WARNING | ...``):
#: notices for a Jupyter operator (an untrusted notebook, a kernel over local TCP),
#: not for the page's user.
_SERVER_WARNING = re.compile(r"^\[[\w.-]+\] WARNING \|")


def _relay(lines, out) -> None:
    """Copy the server's output to `out`, without its WARNING log records."""
    for line in lines:
        if not _SERVER_WARNING.match(line):
            out.write(line)
            out.flush()


class _Stopped(BaseException):
    """SIGTERM (or SIGHUP) arrived: stop the server and clean up, as for Ctrl-C."""


def _listening(port: int) -> bool:
    import socket

    try:
        with socket.create_connection(("127.0.0.1", port), timeout=0.5):
            return True
    except OSError:
        return False


def _stop(proc) -> None:
    """Stop voila and everything it started (its kernel): SIGTERM to its process group,
    SIGKILL after 10 s."""
    import os
    import signal
    import subprocess

    if proc.poll() is not None:
        return
    if not hasattr(os, "killpg"):              # no process groups (Windows)
        proc.terminate()
        proc.wait()
        return
    for sig, wait in ((signal.SIGTERM, 10), (signal.SIGKILL, 5)):
        try:
            os.killpg(proc.pid, sig)
        except ProcessLookupError:
            return
        try:
            proc.wait(timeout=wait)
            return
        except subprocess.TimeoutExpired:
            continue


def serve(config: str = "mdart", overrides: list[str] | None = None, *, port: int = 8866,
          open_browser: bool = False) -> int:
    """Serve the page with voila on ``127.0.0.1:port`` until interrupted.

    The port is checked first (:func:`check_port`) and voila may not move to
    another: the address printed, once voila answers on it, is the one
    served.  Relative paths are read from the caller's folder.  Ctrl-C,
    SIGTERM and SIGHUP stop voila and its kernel (its whole process group)
    and remove the notebook's temporary folder.  Warnings of the server's
    own libraries are not shown.

    Parameters
    ----------
    config : str, optional
        Configuration file or packaged name.
    overrides : list of str, optional
        ``NAME=VALUE`` overrides.
    port : int, optional
        TCP port (0: a free one).
    open_browser : bool, optional
        Open the page in the default browser.

    Returns
    -------
    int
        voila's exit status; 128 + the signal's number after SIGTERM or SIGHUP.

    Raises
    ------
    MissingExtra
        voila is not installed.
    ValueError
        The port is out of range or in use.
    KeyboardInterrupt
        Ctrl-C (after the server is stopped and its folder removed).
    """
    import os
    import shutil
    import signal
    import subprocess
    import sys
    import tempfile
    import threading
    import time

    check_voila()
    port = check_port(port)
    tmp = tempfile.mkdtemp(prefix="tefcore-explore-")
    proc = None

    def stopped(signum, frame):
        raise _Stopped(signum)

    handlers = {}
    if threading.current_thread() is threading.main_thread():   # signals reach it alone
        handlers = {sig: signal.signal(sig, stopped) for sig in
                    (getattr(signal, n) for n in ("SIGTERM", "SIGHUP") if hasattr(signal, n))}
    try:
        path = os.path.join(tmp, "tefcore_explorer.ipynb")
        with open(path, "w", encoding="utf-8") as f:
            f.write(notebook_json(config, overrides, folder=os.getcwd()))
        # JupyterLab extensions that are not for a page (jupytext's, when installed)
        # fail to load in voila's page and print console errors; a list option is
        # given item by item (the list syntax is deprecated in traitlets 5)
        cmd = [sys.executable, "-m", "voila", path, f"--port={port}", "--Voila.port_retries=0",
               "--Voila.ip=127.0.0.1", "--theme=light", "--show_tracebacks=False",
               "--Voila.log_level=WARN"]
        cmd += [f"--VoilaConfiguration.extension_denylist={name}" for name in VOILA_DENIED]
        if not open_browser:
            cmd.append("--no-browser")
        env = {**os.environ, "PYTHONWARNINGS": "ignore"}   # the server's libraries' warnings
        proc = subprocess.Popen(cmd, cwd=tmp, env=env, stdout=subprocess.PIPE,
                                stderr=subprocess.STDOUT, text=True, errors="replace",
                                start_new_session=hasattr(os, "killpg"))
        threading.Thread(target=_relay, args=(proc.stdout, sys.stderr), daemon=True).start()
        while proc.poll() is None and not _listening(port):
            time.sleep(0.2)
        if proc.poll() is None:
            print(f"serving the tefcore explorer at http://127.0.0.1:{port}/ (Ctrl-C stops it)",
                  flush=True)
        return proc.wait()
    except _Stopped as stop:
        return 128 + int(stop.args[0])
    finally:
        if proc is not None:
            _stop(proc)
        for sig, handler in handlers.items():
            signal.signal(sig, handler)
        shutil.rmtree(tmp, ignore_errors=True)
