// SPDX-License-Identifier: GPL-3.0-or-later
// A program using the installed btob library (examples/cpp/CMakeLists.txt): the Lyapunov exponents of one orbit and
// the basins of attraction at one r, the analyses of `btob lyapunov` and `btob basins`, as requests and results.
#include <btob/btob.hpp>

#include <cstdio>
#include <exception>

int main() try {
  std::printf("btob %s\n", btob::version());

  // The projective exponents lambda1 >= lambda2 of the orbit of one direction (per map iteration, natural log).
  btob::lyapunov::OrbitRequest orbit;
  orbit.r = 0.3;
  orbit.point = "1,0.2,-0.5";
  orbit.iterations = 20000;
  orbit.validate();
  const btob::lyapunov::ProjectiveResult lyap = btob::lyapunov::run(orbit);
  std::printf("lyapunov r=0.3 point=1,0.2,-0.5: lambda1 = %.6f +- %.1e, lambda2 = %.6f +- %.1e (%ld iterations)\n",
              lyap.lambda[0].value, lyap.lambda[0].error, lyap.lambda[1].value, lyap.lambda[1].error, lyap.iterations);

  // The attractors at r = 0.3 and the fraction of the sphere of directions each one attracts.
  btob::attractors::BasinsRequest basins;
  basins.r = 0.3;
  basins.grid = "sphere:24x24";
  basins.replicates = 0;
  basins.validate();
  const btob::attractors::BasinsResult res = btob::attractors::run(basins);
  std::printf("basins r=0.3 grid %s: %zu attractors, %zu undecided of %zu points\n", basins.grid.c_str(),
              res.basins.attractors.size(), res.undecided_count, res.points());
  for (std::size_t i = 0; i < res.basins.attractors.size(); ++i) {
    const auto& a = res.basins.attractors[i];
    std::printf("  attractor %d %-12s fraction %.4f [%.4f, %.4f]\n", a.id,
                a.pattern.empty() ? a.key.c_str() : a.pattern.c_str(), res.fraction[i], res.ci_low[i], res.ci_high[i]);
  }
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "btob_example: %s\n", e.what());
  return 1;
}
