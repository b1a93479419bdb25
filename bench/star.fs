// The paper's star (Listing 1, second child): a parametric surface, three outputs per (u, v, w).
function parametric_x(u, v, w) { return (0.3 - 0.1 * sin(v * 5 * pi)) * cos(v * pi) * (4 + cos(u * pi)); }
function parametric_y(u, v, w) { return (0.3 - 0.1 * sin(v * 5 * pi)) * sin(v * pi) * (4 + cos(u * pi)); }
function parametric_z(u, v, w) { return 0.2 * sin(u * pi); }
