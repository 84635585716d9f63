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
"""
from . import _mjarm

__all__ = ["launch_passive", "PassiveViewer", "PassiveViewerOptions"]

PassiveViewer = _mjarm.PassiveViewer
PassiveViewerOptions = _mjarm.PassiveViewerOptions


def launch_passive(model, data=None, *, camera=None, script=None, **options):
    """Opens a passive viewer on ``model`` (an ``mjarm.Robot`` or ``mujoco.MjModel``) showing
    ``data`` (an ``mjarm.Data`` or ``mujoco.MjData``) — or on an ``mjarm.Simulation`` alone, its
    robot and data.

    ``camera`` is a free or model ``mjarm.CameraSpec``; ``script`` scripted input as text (tests
    and demos); any ``PassiveViewerOptions`` field by keyword (``width``, ``height``,
    ``render_hz``, ``title``, ``show_figures``, ``figure_seconds``, ``max_markers``).
    Returns the ``PassiveViewer``, a context manager that closes the window on leaving the block.
    Raises ``mjarm.Error`` when there is no display (set DISPLAY or run under xvfb-run).
    """
    if isinstance(model, _mjarm.Simulation):
        if data is not None:
            raise TypeError("launch_passive(simulation) takes no data: it shows the simulation's")
        model, data = model.robot, model.data
    elif data is None:
        raise TypeError("launch_passive(model, data): the data to show is missing")
    opts = PassiveViewerOptions(**options)
    if camera is not None:
        opts.camera = camera
    if script is not None:
        opts.script = script
    return PassiveViewer(model, data, opts)
