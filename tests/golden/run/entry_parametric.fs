// A parametric surface script: the kernel returns x, y, z; a missing t is allowed.
function parametric_x(u, v, w, t) { return u * cos(2 * pi * v); }
function parametric_y(u, v, w) { return u * sin(2 * pi * v); }
function parametric_z(u, v, w, t) { return t; }
// run: $(1, 0, 0, 5) == 1, 0, 5
// run: $(2, 0.25, 0, 0) ~= -8.74227766e-08, 2, 0
