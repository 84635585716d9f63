// Configure-time probe (cmake/mjarm_find_mujoco.cmake): prints the MuJoCo version when the
// header and the library agree, and both versions with exit code 1 when they do not.
#include <mujoco/mujoco.h>

#include <cstdio>

int main() {
  if (mj_version() != mjVERSION_HEADER) {
    std::printf("the header is version %d but the library is %s (%d)", mjVERSION_HEADER,
                mj_versionString(), mj_version());
    return 1;
  }
  std::printf("%s", mj_versionString());
  return 0;
}
