% SPDX-License-Identifier: GPL-3.0-or-later
% Runs appendix_a1 on the 32 points of the Section 4 grid at the r values given, NN = 4 N collisions (N = 5000
% b-to-b steps), and prints per r: orbits that took a complex acos, orbits with fewer than N b-collisions, and the
% last 100 Re(theta) at b-collisions of each orbit's tail (min/max over the grid).
% Usage: octave-cli --eval "grid_counts([0.072 0.075 0.078])"
function grid_counts(rs)
  N = 5000; NN = 4 * N;
  for r = rs
    ncomplex = 0; nshort = 0; lo = inf; hi = -inf;
    for g = 1:8
      for h = 1:4
        u = [1; -(1+8)/(2+g); -0.1-h]; u = u / norm(u);
        theta0 = atan2(-u(3), u(1));                 % tan(theta) = -z/x (Section 4)
        phi0 = acos(-u(2));                          % cos(phi) = -y (eq. (6.1))
        [T, S] = appendix_a1(theta0, phi0, NN, r);
        b = find(S(3,2:end) == 2) + 1;               % columns recorded at a b-collision
        if any(imag(S(1,:)) ~= 0) || any(imag(S(2,:)) ~= 0), ncomplex = ncomplex + 1; end
        if numel(b) < N, nshort = nshort + 1; end
        tailv = real(S(1, b(max(1, numel(b) - 99):end)));
        lo = min([lo tailv]); hi = max([hi tailv]);
      end
    end
    printf("r = %.4f: complex orbits %d of 32, orbits with fewer than %d b-collisions %d, tail Re(theta) in [%.4g, %.4g]\n", r, ncomplex, N, nshort, lo, hi);
  end
end
