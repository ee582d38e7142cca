#include "cross_section_figure.h"

#include <Eigen/Geometry>
#include <cmath>
#include <map>
#include <sstream>
#include <vector>

namespace fibrecheck {

namespace {

/// The section plane's axes g1, g2 (orthonormal, across the tow axis).
struct SectionAxes {
  Eigen::Vector3d axis, g1, g2;
};

SectionAxes section_axes(const Scene& scene) {
  SectionAxes a;
  a.axis = scene.contact.axis.normalized();
  int k = 0;
  a.axis.cwiseAbs().maxCoeff(&k);
  a.g1 = Eigen::Vector3d::Unit((k + 1) % 3);
  a.g1 = (a.g1 - a.g1.dot(a.axis) * a.axis).normalized();
  a.g2 = a.axis.cross(a.g1);
  return a;
}

/// The fibres cut at mid-length: rows "x y radius |M|", how many, their smallest and largest
/// radius and the box around them (mm).
struct SectionCircles {
  std::string rows;
  int drawn = 0;
  double radius = INFINITY, largest_radius = 0.0;
  Eigen::Vector2d lo{INFINITY, INFINITY}, hi{-INFINITY, -INFINITY};
};

SectionCircles section_circles(const Scene& scene, const Result& result, const SectionAxes& a) {
  const double cos_parallel = std::cos(scene.contact.parallel_angle_deg * M_PI / 180.0);
  std::map<std::string, std::size_t> index;
  for (std::size_t i = 0; i < result.fibres.size(); ++i) index[result.fibres[i].id] = i;
  SectionCircles c;
  std::ostringstream circles;
  for (const FibreSpec& f : scene.fibres) {
    const Eigen::Vector3d t = (f.end - f.start).normalized();
    if (std::fabs(t.dot(a.axis)) < cos_parallel || !index.count(f.id)) continue;
    const FibreResult& r = result.fibres[index[f.id]];
    if (r.displacement.empty()) continue;
    const std::size_t j = (r.displacement.size() - 1) / 2;
    const double s = r.displacement.size() > 1 ? double(j) / (r.displacement.size() - 1) : 0.0;
    const Eigen::Vector3d x = f.start + s * (f.end - f.start) + r.displacement[j];
    const double M = j < r.moment.size() ? r.moment[j].norm() : 0.0;
    circles << x.dot(a.g1) << " " << x.dot(a.g2) << " " << f.radius << " " << M << "\n";
    c.lo = c.lo.cwiseMin(Eigen::Vector2d(x.dot(a.g1) - f.radius, x.dot(a.g2) - f.radius));
    c.hi = c.hi.cwiseMax(Eigen::Vector2d(x.dot(a.g1) + f.radius, x.dot(a.g2) + f.radius));
    c.radius = std::min(c.radius, f.radius);
    c.largest_radius = std::max(c.largest_radius, f.radius);
    ++c.drawn;
  }
  c.rows = circles.str();
  return c;
}

/// The contact forces of the middle slice as vectors "x y dx dy" from each contact point, both
/// ways (the force on fibres[0] and its reaction), and the largest of each kind (N).
struct SectionForces {
  std::string normal, friction;
  double largest_force = 0.0, largest_friction = 0.0;
};

SectionForces section_forces(const Result& result, const SectionAxes& a, double radius) {
  SectionForces out;
  // The contact points nearest the middle slice, one per pair.
  std::vector<const ContactPoint*> points;
  for (const ContactResult& pair : result.contacts) {
    if (pair.kind == "point" || pair.points.empty()) continue;
    const ContactPoint* nearest = &pair.points.front();
    for (const ContactPoint& p : pair.points)
      if (std::fabs(p.position - 0.5) < std::fabs(nearest->position - 0.5)) nearest = &p;
    if (std::fabs(nearest->position - 0.5) > 0.05) continue;
    points.push_back(nearest);
    out.largest_force = std::max(out.largest_force, nearest->force.norm());
    out.largest_friction = std::max(out.largest_friction, nearest->friction_force.norm());
  }
  std::ostringstream normal, friction;
  for (const ContactPoint* p : points) {
    // The friction force on its own scale: it is at most μ times the normal force.
    const Eigen::Vector3d n = p->normal_force / out.largest_force * radius;
    const Eigen::Vector3d f =
        out.largest_friction > 0.0
            ? Eigen::Vector3d(p->friction_force / out.largest_friction * radius)
            : Eigen::Vector3d::Zero();
    for (double sign : {1.0, -1.0}) {
      normal << p->point.dot(a.g1) << " " << p->point.dot(a.g2) << " " << sign * n.dot(a.g1) << " "
             << sign * n.dot(a.g2) << "\n";
      if (f.norm() > 0.0)
        friction << p->point.dot(a.g1) << " " << p->point.dot(a.g2) << " " << sign * f.dot(a.g1)
                 << " " << sign * f.dot(a.g2) << "\n";
    }
  }
  out.normal = normal.str();
  out.friction = friction.str();
  return out;
}

/// Each wall seen edge-on in the section: a line through its point along its in-plane direction,
/// `far` (mm) each way (clipped by the picture's ranges).
std::string section_walls(const Scene& scene, const SectionAxes& a, double far) {
  std::ostringstream walls;
  for (const WallSpec& w : scene.walls) {
    const Eigen::Vector2d n(w.normal.dot(a.g1), w.normal.dot(a.g2));
    if (n.norm() < 1e-9) continue;
    const Eigen::Vector2d p(w.point.dot(a.g1), w.point.dot(a.g2)), d(-n.y(), n.x());
    walls << (p - far * d).x() << " " << (p - far * d).y() << "\n"
          << (p + far * d).x() << " " << (p + far * d).y() << "\n\n";
  }
  return walls.str();
}

/// A force in gnuplot's enhanced text: "1.2×10^{-5} N".
std::string force_text(double force) {
  const int exponent = static_cast<int>(std::floor(std::log10(force)));
  std::ostringstream text;
  text.precision(2);
  text << force / std::pow(10.0, exponent) << "×10^{" << exponent << "} N";
  return text.str();
}

/// The forces' scale drawn above the picture: for the normal forces and, where there are any,
/// the friction, a bar one radius long (in the picture's units) after the force it stands for.
std::string force_scale(const SectionForces& forces, double radius) {
  std::ostringstream gp;
  const bool friction = forces.largest_friction > 0.0;
  gp << "set tmargin " << (friction ? 4 : 3) << "\n";
  auto bar = [&](double row, const std::string& colour, const std::string& what, double force) {
    gp << "set label '" << what << " " << force_text(force) << "' at graph 0.5, graph " << row
       << " right offset -1, 0 front\n"
       << "set arrow from graph 0.5, graph " << row << " rto first " << radius
       << ", first 0 nohead lw 3 lc rgb '" << colour << "' front\n";
  };
  bar(friction ? 1.09 : 1.04, "#e0a000", "normal force", forces.largest_force);
  if (friction) bar(1.035, "#e00000", "friction force", forces.largest_friction);
  return gp.str();
}

}  // namespace

void draw_cross_section(ReportPage& page, const std::string& name, const std::string& what,
                        const Scene& scene, const Result& result) {
  const SectionAxes axes = section_axes(scene);
  const SectionCircles circles = section_circles(scene, result, axes);
  if (circles.drawn < 3) return;
  const SectionForces forces = section_forces(result, axes, circles.radius);
  // A section no contact force crosses shows circles only: not a figure worth a number.
  if (!(forces.largest_force > 0.0)) return;
  const std::string walls = section_walls(scene, axes, 10.0 * (circles.hi - circles.lo).norm());
  const Eigen::Vector2d pad = Eigen::Vector2d::Constant(0.3 * circles.largest_radius);
  const Eigen::Vector2d lo = circles.lo - pad, hi = circles.hi + pad;
  const std::string ranges = "set xrange [" + std::to_string(lo.x()) + ":" +
                             std::to_string(hi.x()) + "]\nset yrange [" + std::to_string(lo.y()) +
                             ":" + std::to_string(hi.y()) + "]\n";
  page.figure(
      name,
      what +
          ", drawn like the seed's Figure 4.14: the fibres at their deformed centres at "
          "mid-length, the rim coloured by the bending moment |M| there, the walls in grey, and "
          "the contact forces of that slice as lines from each contact point: normal parts in "
          "orange (the largest, " +
          sci(forces.largest_force) + " N, one radius long, as the bar above)" +
          (forces.largest_friction > 0.0
               ? ", friction forces in red on their own scale (the largest, " +
                     sci(forces.largest_friction) + " N, one radius long, the second bar)."
               : std::string(".")),
      "set size ratio -1\n" + ranges + force_scale(forces, circles.radius) +
          "set xlabel 'cross-section axis 1 (mm)'\nset ylabel 'cross-section axis 2 (mm)'\nset "
          "cblabel '|M| (N mm)'\nset cbrange [0:*]\nset rmargin 14\nset palette defined (0 "
          "'#2040c0', "
          "0.5 '#20b040', 1 '#e02020')\nset key off\nset grid\nset format cb '%.1t×10^{%T}'\nset "
          "clip "
          "two\nplot @DATA0@ using 1:2:3:4 with circles lc palette lw 3 fs empty, @DATA1@ using "
          "1:2:3:4 with vectors nohead lw 3 lc rgb '#e0a000', @DATA2@ using 1:2:3:4 with vectors "
          "nohead lw 3 lc rgb '#e00000', @DATA3@ using 1:2 with lines lw 2 lc rgb '#606060'",
      {{circles.rows},
       {rows_or_nan(forces.normal, 4)},
       {rows_or_nan(forces.friction, 4)},
       {rows_or_nan(walls)}});
}

}  // namespace fibrecheck
