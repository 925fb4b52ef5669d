% SPDX-License-Identifier: GPL-3.0-or-later
% The trigonometric algorithm of the paper's Appendix A.1, as printed (MATLAB; runs unchanged in GNU Octave, whose
% acos returns a complex number outside [-1, 1] as MATLAB's does).  Inputs theta0, phi0 (the b-state of eq. (2.17)),
% NN collisions, r.  A, B, C are the collision matrices of eq. (2.6) (column i carries the collision of pair i,
% alpha = (1 + r)/2).  Outputs as in the paper: Trajectory (7 x NN+1), SphericalTrajectory (3 x NN+1).
function [Trajectory, SphericalTrajectory] = appendix_a1(theta0, phi0, NN, r)
  a = (1 + r) / 2;
  A = eye(3); A(1,1) = -r; A(2,1) = a;
  B = eye(3); B(1,2) = a; B(2,2) = -r; B(3,2) = a;
  C = eye(3); C(2,3) = a; C(3,3) = -r;
  Trajectory = zeros(7,NN+1);
  SphericalTrajectory = zeros(3,NN+1);
  X = [sin(theta0);0;cos(theta0)];
  V = cos(phi0)*[cos(theta0);0;-sin(theta0)] + sin(phi0)*[0;1;0];
  Contact_pair = 2;
  Trajectory(:,1) = [X;V;Contact_pair];
  SphericalTrajectory(:,1) = [theta0;phi0;Contact_pair];
  j = 2;
  while j < NN+2
    if Contact_pair == 1
      theta = acos(X(2,1));
      CosPhi = V(3,1)/cos(theta);
      phi = acos(CosPhi);
      if phi < pi/2
        X = [cos(theta)*sin(phi);0;cos(phi)]; X = X/norm(X);
        V = B*V; V = V - dot(V,X)*X; V = V/norm(V);
        Contact_pair = 2;
      elseif phi > pi/2
        X = [sin(theta)*sin(phi);-cos(phi);0]; X = X/norm(X);
        V = C*V; V = V - dot(V,X)*X; V = V/norm(V);
        Contact_pair = 3;
      end
    elseif Contact_pair == 2
      theta = acos(X(3,1));
      CosPhi = V(1,1)/cos(theta);
      phi = acos(CosPhi);
      if phi < pi/2
        X = [cos(phi);cos(theta)*sin(phi);0]; X = X/norm(X);
        V = C*V; V = V - dot(V,X)*X; V = V/norm(V);
        Contact_pair = 3;
      elseif phi > pi/2
        X = [0;sin(theta)*sin(phi);-cos(phi)]; X = X/norm(X);
        V = A*V; V = V - dot(V,X)*X; V = V/norm(V);
        Contact_pair = 1;
      end
    elseif Contact_pair == 3
      theta = acos(X(1,1));
      CosPhi = V(2,1)/cos(theta);
      phi = acos(CosPhi);
      if phi < pi/2
        X = [0;cos(phi);cos(theta)*sin(phi)]; X = X/norm(X);
        V = A*V; V = V - dot(V,X)*X; V = V/norm(V);
        Contact_pair = 1;
      elseif phi > pi/2
        X = [-cos(phi);0;sin(theta)*sin(phi)]; X = X/norm(X);
        V = B*V; V = V - dot(V,X)*X; V = V/norm(V);
        Contact_pair = 2;
      end
    end
    Trajectory(:,j) = [X; V; Contact_pair];
    SphericalTrajectory(:,j) = [theta; phi; Contact_pair];
    j = j+1;
  end
end
