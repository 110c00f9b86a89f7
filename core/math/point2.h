// A point in the plane: texture coordinates, disk and barycentric samples.
#pragma once

namespace pf {

struct Point2 {
    float x = 0, y = 0;
};

}  // namespace pf
