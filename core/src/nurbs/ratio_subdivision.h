// The maximum of a rational function g = a / w over the unit square, a and w in Bernstein form of degree (p, q)
// with w > 0, bounded by subdividing the forms. The largest coefficient ratio bounds g over the square, second
// order in its size; the bound of a piece whose ratios do not vary along one direction (a surface of revolution
// seen from a point on its axis: the squared distance does not change around it) only improves by splitting
// across the other. So such forms are halved across the direction their ratios curve most, the piece with the
// highest bound first, instead of in both directions as the patch tree does: a circle of minima then costs
// a few dozen splits of one node's forms, not thousands of nodes. Forms curving both ways about as much are
// left as they are (the tree's quadrants do as well). Internal.
#pragma once

namespace unidist::nurbs {

struct RatioRefinement {
  double enough;     // stop once the bound is at most this
  double allowance;  // added to every piece's bound for rounding (per unit of a / w), before subdivision
  int budget;        // most pieces halved
};

struct RatioBound {
  double upper;  // g <= upper over the square
  double reached;  // the greatest g at a piece corner found on the way: the true maximum is at least this
  int splits;
};

/// a and w: (p + 1)(q + 1) coefficients, u-major (a[i (q + 1) + j]); every w coefficient must be positive.
RatioBound subdividedRatioBound(int p, int q, const double* a, const double* w, const RatioRefinement& refine);

}  // namespace unidist::nurbs
