// A tube about a circle separating two surfaces near their closest pair where neither a plane nor a ball can:
// one surface (the inner) is a saddle there, curving toward the other along one principal direction and away
// along the other, as the inside of a ring does. The tube (a torus) through the contact with the inner's
// principal curvatures holds the inner surface near it (a torus's inside exactly: its own core circle), and the
// outer surface stays outside the tube widened by the gap. The distance to a circle is 1-Lipschitz, so a node
// inside the tube of radius s and one outside the tube of radius s + g are at least g apart. "Inside the tube
// of radius s" is the sign of the torus's quartic, (|x|² + R² − s²)² − 4R²ρ² (ρ: distance from the axis), on the
// node: its Bernstein coefficients times W⁴, of degree (4p, 4q), exact for a torus's own patches at any size and
// second order in the size elsewhere; next to the contact, where that order falls short of the tolerance's
// margin, the quartic is convex and its extreme is proved exactly (support_bound.h). Two linked rings are the
// case this is for. Internal.
#pragma once

#include "nurbs/patch_tree.h"
#include "nurbs/separator_contact.h"

#include <optional>
#include <vector>

namespace unidist::nurbs {

class SupportTube {
 public:
  /// The tube for the closest pair, separating pairs of nodes by `needed`: the inner surface tested against
  /// radius r + ¼·tolerance, the outer against r + ¼·tolerance + needed. None where neither side is a saddle
  /// curving toward the other.
  static std::optional<SupportTube> fit(const SeparatorContact& contact, double needed, double tolerance);

  /// Takes a fresh fit's outer radius, when it is about this tube (centre, core radius, axis and inner radius within
  /// `slack`) and no wider: every proof made stays valid (outside a tube is outside a narrower one), the outer
  /// side's refusals are forgotten. A refit at a lower best pair on the same ring (the first Newton ends are
  /// rarely the minimum) then spares all the forms made. False, and this tube unchanged, otherwise.
  bool narrowTo(const SupportTube& fresh, double slack);

  /// The proved distance between the two nodes when the tube separates them (at least the `needed` it was made
  /// for), else −infinity. Certificates are kept per node.
  double gap(const PatchNode& na, const PatchNode& nb);

  /// After a gap() that did not separate: +1 when only B's node was not proved on its side, −1 when only A's, else
  /// 0 (splitting the proved one would settle nothing).
  int lastUnproved() const { return lastUnproved_; }

  bool innerIsA() const { return innerIsA_; }
  double coreRadius() const { return R_; }

 private:
  struct Circle {
    Eigen::Vector3d centre, axis;
  };
  /// A part of a patch proved on its side: so is every node inside it (a subpatch of a part inside the tube is
  /// inside it), which spares their forms; the search visits the larger nodes first.
  struct ProvedBox {
    double s0, s1, t0, t1;
  };
  using ProvedBoxes = std::vector<std::vector<ProvedBox>>;  // per patch: the search asks ~50 times per node made
  static bool covered(const ProvedBoxes& boxes, const PatchNode& node);
  /// What one side knows: each node's verdict, the parts proved, and the last node asked (the search visits a
  /// node's pairs in a row: a ring's 16 root patches against each other's, a node's four children against one).
  struct Side {
    NodeMemo memo;
    ProvedBoxes boxes;
    const PatchNode* lastNode = nullptr;
    bool lastResult = false;
  };
  /// The Bernstein coefficients (degree (4p, 4q), in the scratch) of the tube's quartic over the net,
  /// (|y|² + (R² − s²)W²)² − 4R²(|y|² − z²)W² with y = X − centre·W, z = axis·y: negative inside the tube of
  /// radius s, positive outside. `allowance`: how far a coefficient may be off by rounding.
  std::vector<double>& quarticOf(const RationalBezierPatch& net, const Circle& circle, double s, double& allowance);
  /// Is the node inside (inside = true) the tube of radius s about the circle, or outside it? Proved. The last
  /// node asked is answered again at once; others go to verdict().
  bool proved(Side& side, const PatchNode& node, const Circle& circle, double s, bool inside);
  bool verdict(Side& side, const PatchNode& node, const Circle& circle, double s, bool inside);

  bool innerIsA_ = true;
  int lastUnproved_ = 0;
  double R_ = 0, inner_ = 0, outer_ = 0;  // core circle radius; the tube radii the two sides are tested against
  Circle circleA_, circleB_;               // the circle in A's and in B's frame
  Side innerSide_, outerSide_;
  struct Scratch {  // the quartic's forms, kept between nodes (one search makes tens of them)
    std::vector<Eigen::Vector3d> y;
    std::vector<double> axial, w, yy, zz, ww, u, rho2, quartic;
  } scratch_;
};

}  // namespace unidist::nurbs
