// Preloaded (LD_PRELOAD) by test_mujoco_interop.py in front of the real MuJoCo library, it makes
// that library report another version through mj_version() (everything else stays MuJoCo's): the
// CLI at start and the Python extension at import must refuse it, naming both versions.
extern "C" int mj_version(void) { return 3003006; }
