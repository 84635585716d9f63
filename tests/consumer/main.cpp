// Loads a bundled arm from the installed share directory and prints its degrees of freedom.
#include <iostream>

#include "mjarm/model/robot.hpp"

int main() {
  const mjarm::Robot robot = mjarm::Robot::bundled("panda");
  std::cout << robot.name() << " nq=" << robot.nq() << "\n";
  return robot.nq() >= 7 ? 0 : 1;
}
