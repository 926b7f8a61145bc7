// The letters that name the coordinate axes in field names, case files and messages.
#pragma once

namespace rktsph {

/// "x", "y" or "z" for axis 0, 1 or 2.
constexpr const char* axis_letter(int axis) {
  return axis == 0 ? "x" : (axis == 1 ? "y" : "z");
}

}  // namespace rktsph
