"""Tasks written in Python: subclass ``mjarm.EnvTask`` and give an instance to
``mjarm.Environment`` (or ``mjarm.VectorEnvironment``), which runs it like its own tasks::

    class Reach(mjarm.EnvTask):
        name = "py_reach"

        def __init__(self):
            super().__init__(robot, "tool")          # the model (torque motors) and the arm's frame

        def action_spec(self):                        # any bounded array (None: the action space's)
            return mjarm.ArraySpec("velocity", [3], [-0.2] * 3, [0.2] * 3)

        def map_action(self, context, action):        # onto the environment's action space
            return np.concatenate([action, np.zeros(3)])   # ee_velocities: [v; w]

        def initialize_episode(self, sim, rng):       # rng: the episode's numpy Generator
            sim.reset()
            self.target = rng.uniform([0.3, -0.2, 0.3], [0.5, 0.2, 0.5])

        def observation_specs(self):
            return [mjarm.ArraySpec("target", [3])]

        def observe(self, name, context):
            return self.target

        def reward(self, context):
            return -np.linalg.norm(context.X_WE.p - self.target)

The environment calls the hooks in this order, never concurrently on one task::

    reset:  initialize_episode -> observe (each task observation)
    step:   [map_action ->] before_step -> physics -> after_step -> observe -> reward -> terminated

Each hook runs with the GIL taken for its call only (the environment steps with it released).
``context`` is a ``mjarm.StepContext``: ``X_WE``, ``V_WE``, ``step``, ``time`` and ``data`` (the
simulation's state, lent for the call). An exception a hook raises ends the episode and is
raised by ``reset``/``step`` with its traceback; ``reset`` starts a clean one.

For a ``VectorEnvironment`` each environment runs its own ``clone()`` of the task, by default a
shallow copy: assign episode state (``self.target = ...``) rather than changing a shared array in
place, or override ``clone``.
"""
import copy

__all__ = ["EnvTask"]


class EnvTask:
    """A learning task written in Python (see the module's documentation)."""

    #: short name, shown by the environment
    name = "python"
    #: one line on what the task asks
    description = "a task written in Python"

    def __init__(self, robot, chain):
        """``robot``: an ``mjarm.Robot`` or ``mujoco.MjModel`` with torque motors on the arm's
        joints; ``chain``: an ``mjarm.Chain`` of it or the name of its end-effector site."""
        self.robot = robot
        self.chain = chain

    def clone(self):
        """An independent copy for another environment of a batch (default: a shallow copy)."""
        return copy.copy(self)

    def action_spec(self):
        """The task's own action (an ``mjarm.ArraySpec`` with finite bounds), mapped by
        ``map_action`` onto the environment's action space; None: the action space's own."""
        return None

    def map_action(self, context, action):
        """With ``action_spec``: the environment's action-space values (an array of its size)
        for the clipped task ``action``; clipped into the space's bounds afterwards."""
        raise NotImplementedError(f"{type(self).__name__} has an action_spec but no map_action")

    def observation_specs(self):
        """The task's own observations: a list of ``mjarm.ArraySpec``."""
        return []

    def default_observations(self):
        """Observation names used when the environment is given none (None: the joint
        positions and velocities, the end-effector pose and the task's own)."""
        return None

    def initialize_episode(self, sim, rng):
        """Starts an episode: put ``sim`` (an ``mjarm.Simulation``) in its start state and draw
        the episode's goal from ``rng`` (a ``numpy.random.Generator`` seeded by the episode)."""
        sim.reset()

    def before_step(self, context, action):
        """Before the physics, with the clipped action."""

    def after_step(self, context):
        """After the physics."""

    def observe(self, name, context):
        """The value of the task's observation ``name`` (an array of its spec's size)."""
        raise NotImplementedError(f"{type(self).__name__} declares observation '{name}' but "
                                  "defines no observe")

    def reward(self, context):
        """The reward of the step that led to ``context``."""
        raise NotImplementedError(f"{type(self).__name__} defines no reward")

    def terminated(self, context):
        """True when the episode ends here by the task's own rule (discount 0)."""
        return False
