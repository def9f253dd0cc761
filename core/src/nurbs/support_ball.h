// A ball separating two surfaces near their closest pair where a plane cannot: one surface (the inner one)
// curves away from the other more than a sphere of radius ρ does, and the other stays outside the concentric
// sphere of radius ρ + d. With c the centre, |a − b| >= |a − c| − |b − c| for any points, so every pair of
// nodes is at least (least distance from c over the outer node) − (greatest over the inner node) apart. Both
// extremes are certified exactly where the node holds the touching point (support_bound.h), so the nodes at the
// closest pair are settled at any size, as the support plane settles them at a convex contact. It needs the
// inner surface strictly convex there and the outer one curving toward it less than 1 / (ρ + d): a saddle or
// a concave side against a convex one. Internal.
#pragma once

#include "nurbs/patch_tree.h"
#include "nurbs/separator_contact.h"

#include <optional>

namespace unidist::nurbs {

class SupportBall {
 public:
  /// The ball for the closest pair; none when neither side is curved enough to fit one.
  static std::optional<SupportBall> fit(const SeparatorContact& contact);

  /// A proved lower bound of the distance between the two nodes (rounding of the nets aside, as for the other
  /// bounds); certificates are made (and kept per node) only while the bound falls short of `needed`. `parentA`,
  /// `parentB`: nodes holding na and nb (their parents, or themselves), whose certified extremes they inherit
  /// (a subpatch is no farther, and no nearer, than the patch holding it); null at the roots.
  double gap(const PatchNode& na, const PatchNode& nb, double needed, const PatchNode* parentA = nullptr,
             const PatchNode* parentB = nullptr);

  double radius() const { return radius_; }
  bool innerIsB() const { return innerIsB_; }

 private:
  /// The least (near) or greatest distance from the centre over the node, certified (near: 0 and far: +inf
  /// when not proved).
  /// Exact (by concavity) only for a node at the touching point `contact`; elsewhere the surface is clear of the
  /// sphere by a margin and the coefficient bound, second order in the node size, is what is worth its cost.
  /// `enough`: the value that would settle the pairs at hand (certifyDistanceExtreme sharpens a bound short of it).
  double certified(NodeMemo& memo, const PatchNode& node, const PatchNode* parent, const Eigen::Vector3d& centre,
                   const Eigen::Vector3d& contact, bool farthest, double enough);

  bool innerIsB_ = true;
  double radius_ = 0;
  Eigen::Vector3d centreA_ = Eigen::Vector3d::Zero(), centreB_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d contactA_ = Eigen::Vector3d::Zero(), contactB_ = Eigen::Vector3d::Zero();  // pA, pB, own frames
  NodeMemo nearA_, farA_, nearB_, farB_;
};

}  // namespace unidist::nurbs
