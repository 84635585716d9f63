"""A window on your own loop, as ``mujoco.viewer.launch_passive``::

    import mjarm.viewer

    with mjarm.viewer.launch_passive(model, data) as viewer:   # or launch_passive(sim)
        while viewer.is_running():
            mujoco.mj_step(model, data)
            viewer.add_sphere(target, 0.02)     # markers go with the next sync
            viewer.plot("error", error)          # the "Your plots" figure
            viewer.sync()

The window runs in a thread of its own; ``sync()`` copies the state under a lock and returns,
never waiting for a frame. Double-click selects a body; Ctrl + right drag pulls it, Ctrl + left
drag turns it, through the data's ``xfrc_applied`` (written at each ``sync``, zeroed when the drag
ends), as MuJoCo's simulate does. See docs/viewer.md.

Without a display, ``launch_passive(model, data, web=True)`` serves the model to a browser
instead (the replay page's three.js scene, live): open ``viewer.url`` (127.0.0.1;
``host="0.0.0.0"`` needs the token within the url). ``sync()`` publishes the poses and returns at
once; it draws no markers or plots. A build without the page (MJARM_WEB) raises ``mjarm.Error``
saying how to get it.
"""
from . import _mjarm

__all__ = ["launch_passive", "PassiveViewer", "PassiveViewerOptions", "PassiveWebViewer",
           "LiveServerOptions"]

PassiveViewer = _mjarm.PassiveViewer
PassiveViewerOptions = _mjarm.PassiveViewerOptions
PassiveWebViewer = _mjarm.PassiveWebViewer
LiveServerOptions = _mjarm.LiveServerOptions


def launch_passive(model, data=None, *, web=False, camera=None, script=None, **options):
    """Opens a passive viewer on ``model`` (an ``mjarm.Robot`` or ``mujoco.MjModel``) showing
    ``data`` (an ``mjarm.Data`` or ``mujoco.MjData``) — or on an ``mjarm.Simulation`` alone, its
    robot and data.

    ``camera`` is a free or model ``mjarm.CameraSpec``; ``script`` scripted input as text (tests
    and demos); any ``PassiveViewerOptions`` field by keyword (``width``, ``height``,
    ``render_hz``, ``title``, ``show_figures``, ``figure_seconds``, ``max_markers``).
    Returns the ``PassiveViewer``, a context manager that closes the window on leaving the block.
    Raises ``mjarm.Error`` when there is no display (set DISPLAY or run under xvfb-run).

    ``web=True``: no window; a ``PassiveWebViewer`` serving the bodies to browsers at its ``url``,
    its options ``LiveServerOptions`` fields by keyword (``host``, ``port``, ``require_token``,
    ``send_rate``, ...).
    """
    if isinstance(model, _mjarm.Simulation):
        if data is not None:
            raise TypeError("launch_passive(simulation) takes no data: it shows the simulation's")
        model, data = model.robot, model.data
    elif data is None:
        raise TypeError("launch_passive(model, data): the data to show is missing")
    if web:
        if camera is not None or script is not None:
            raise TypeError("launch_passive(web=True) draws no camera view and runs no script")
        return PassiveWebViewer(model, data, LiveServerOptions(**options))
    opts = PassiveViewerOptions(**options)
    if camera is not None:
        opts.camera = camera
    if script is not None:
        opts.script = script
    return PassiveViewer(model, data, opts)
