// The paper's snail (Listing 1, first child): a parametric surface, three outputs per (u, v, w).
function parametric_x(u, v, w) { return 0.03 * pi * v * (10 + 5 * cos(pi * u)) * cos(3 * pi * v); }
function parametric_y(u, v, w) { return 0.03 * pi * v * (10 + 5 * cos(pi * u)) * sin(3 * pi * v); }
function parametric_z(u, v, w) { return 0.03 * pi * v * (6 + 5 * sin(pi * u)); }
