#include "cli/demo_scene.h"

namespace skyband::cli {

DemoScene make_demo_scene() {
  DemoScene d;
  // Ground 200 m × 200 m at z = 0 (two triangles).
  auto& s = d.soup;
  s.vertices = {Vec3(-100, -100, 0), Vec3(100, -100, 0), Vec3(100, 100, 0), Vec3(-100, 100, 0)};
  s.triangles = {{0, 1, 2}, {0, 2, 3}};
  // A street running north–south (x ∈ [−6, 6], 12 m wide) between two rows of buildings,
  // 20 m deep, with a 10 m cross street at y ∈ [−5, 5] on the east side.
  append_box(s, Vec3(-26, -60, 0), Vec3(-6, 60, 18));  // west row, 18 m
  append_box(s, Vec3(6, -60, 0), Vec3(26, -5, 12));    // east row south, 12 m
  append_box(s, Vec3(6, 5, 0), Vec3(26, 60, 24));      // east row north, 24 m
  append_box(s, Vec3(30, -20, 0), Vec3(40, 20, 30));   // a tower behind the east row
  const Vec3 up(0, 0, 1);
  d.points = {
      {"open ground far away", {Vec3(-80, -80, 0), up}},
      {"street centre", {Vec3(0, -30, 0), up}},
      {"street, 1 m from west wall", {Vec3(-5, -30, 0), up}},
      {"street at the cross street", {Vec3(0, 0, 0), up}},
      {"west facade, ground floor", {Vec3(-6, -30, 1.5), Vec3(1, 0, 0)}},
      {"west facade, top floor", {Vec3(-6, -30, 16.5), Vec3(1, 0, 0)}},
      {"east facade (12 m row), 1st floor", {Vec3(6, -30, 4.5), Vec3(-1, 0, 0)}},
      {"roof of the 12 m row", {Vec3(16, -30, 12), up}},
      {"roof of the tower", {Vec3(35, 0, 30), up}},
      {"cross street floor", {Vec3(16, 0, 0), up}},
  };
  return d;
}

}  // namespace skyband::cli
