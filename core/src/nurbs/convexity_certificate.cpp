#include "nurbs/convexity_certificate.h"

#include "nurbs/binomial.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

namespace unidist::nurbs {
namespace {

constexpr double kSlack = 1e-11;      // relative to a form's magnitude: what counts as >= 0 (rounding)
constexpr int kMaxSplits = 12;        // halvings per form (alternating u and v) before a sign is given up
constexpr double kEdgeMatch = 1e-9;   // edges' control points this close (× size) are one edge

/// A polynomial in tensor Bernstein form of degree (p, q), coefficients u-major, with the magnitude of the
/// products it sums (the scale of its rounding). Its own product and halving: the forms here reach degree
/// 8n − 4, beyond the fixed-size tables of bernstein_product.h and ratio_subdivision.cpp (degree kMaxNurbsDegree).
struct Form {
  int p = 0, q = 0;
  std::vector<double> c;
  double magnitude = 0;

  double& at(int i, int j) { return c[static_cast<std::size_t>(i * (q + 1) + j)]; }
  double at(int i, int j) const { return c[static_cast<std::size_t>(i * (q + 1) + j)]; }
};

Form zeroForm(int p, int q) { return {p, q, std::vector<double>(static_cast<std::size_t>((p + 1) * (q + 1)), 0.0), 0}; }

Form measured(Form f) {
  for (double x : f.c) f.magnitude = std::max(f.magnitude, std::abs(x));
  return f;
}

/// The product: Bernstein product weights sum to one per coefficient, so magnitudes multiply.
Form multiply(const Form& x, const Form& y) {
  Form out = zeroForm(x.p + y.p, x.q + y.q);
  for (int i = 0; i <= x.p; ++i)
    for (int j = 0; j <= x.q; ++j)
      for (int k = 0; k <= y.p; ++k)
        for (int l = 0; l <= y.q; ++l)
          out.at(i + k, j + l) += x.at(i, j) * y.at(k, l) * binomial(x.p, i) * binomial(y.p, k) /
                                  binomial(out.p, i + k) * binomial(x.q, j) * binomial(y.q, l) / binomial(out.q, j + l);
  out.magnitude = x.magnitude * y.magnitude;
  return out;
}

/// The same polynomial in degree (p, q) >= its own (degree elevation, one step at a time).
Form elevated(Form f, int p, int q) {
  while (f.p < p) {
    Form g = zeroForm(f.p + 1, f.q);
    for (int i = 0; i <= g.p; ++i)
      for (int j = 0; j <= g.q; ++j) {
        const double a = static_cast<double>(i) / g.p;
        g.at(i, j) = (i > 0 ? a * f.at(i - 1, j) : 0.0) + (i < g.p ? (1 - a) * f.at(i, j) : 0.0);
      }
    g.magnitude = f.magnitude;
    f = std::move(g);
  }
  while (f.q < q) {
    Form g = zeroForm(f.p, f.q + 1);
    for (int i = 0; i <= g.p; ++i)
      for (int j = 0; j <= g.q; ++j) {
        const double a = static_cast<double>(j) / g.q;
        g.at(i, j) = (j > 0 ? a * f.at(i, j - 1) : 0.0) + (j < g.q ? (1 - a) * f.at(i, j) : 0.0);
      }
    g.magnitude = f.magnitude;
    f = std::move(g);
  }
  return f;
}

/// x + sign·y, in the larger of their degrees (a derivative of a degree-1 direction is a zero form of degree 0
/// there, so forms meant to match can differ).
Form combine(Form x, Form y, double sign) {
  const int p = std::max(x.p, y.p), q = std::max(x.q, y.q);
  x = elevated(std::move(x), p, q);
  y = elevated(std::move(y), p, q);
  for (std::size_t k = 0; k < x.c.size(); ++k) x.c[k] += sign * y.c[k];
  x.magnitude += y.magnitude;
  return x;
}

/// A 4-vector of forms (a homogeneous net or a derivative of one).
using Net4 = std::array<Form, 4>;

Net4 netOf(const RationalBezierPatch& patch) {
  Net4 n;
  for (int r = 0; r < 4; ++r) {
    n[r] = zeroForm(patch.degreeU, patch.degreeV);
    for (int i = 0; i <= patch.degreeU; ++i)
      for (int j = 0; j <= patch.degreeV; ++j) n[r].at(i, j) = patch.at(i, j)[r];
    n[r] = measured(n[r]);
  }
  return n;
}

/// The derivative along u (direction 0) or v: degree one less (a zero form of degree 0 from degree 0).
Net4 derivative(const Net4& n, int direction) {
  Net4 d;
  for (int r = 0; r < 4; ++r) {
    const Form& f = n[r];
    const int deg = direction == 0 ? f.p : f.q;
    if (deg == 0) {
      d[r] = zeroForm(f.p, f.q);
      continue;
    }
    d[r] = direction == 0 ? zeroForm(f.p - 1, f.q) : zeroForm(f.p, f.q - 1);
    for (int i = 0; i <= d[r].p; ++i)
      for (int j = 0; j <= d[r].q; ++j)
        d[r].at(i, j) = deg * (direction == 0 ? f.at(i + 1, j) - f.at(i, j) : f.at(i, j + 1) - f.at(i, j));
    d[r] = measured(d[r]);
  }
  return d;
}

/// C with C·X = det[P, P_u, P_v, X], times σ: expanding along X's column, C_r = (−1)^(r+1) times the 3×3 minor
/// of rows ≠ r, each minor expanded along P's column into 2×2 minors of P_u and P_v.
Net4 orientedCross(const Net4& P, const Net4& Pu, const Net4& Pv, int orientation) {
  Form minor2[4][4];
  for (int b = 0; b < 4; ++b)
    for (int c = b + 1; c < 4; ++c) minor2[b][c] = combine(multiply(Pu[b], Pv[c]), multiply(Pu[c], Pv[b]), -1);
  Net4 C;
  for (int r = 0; r < 4; ++r) {
    std::array<int, 3> rows{};
    int k = 0;
    for (int x = 0; x < 4; ++x)
      if (x != r) rows[static_cast<std::size_t>(k++)] = x;
    const auto [a, b, c] = rows;
    Form det3 = combine(combine(multiply(P[a], minor2[b][c]), multiply(P[b], minor2[a][c]), -1),
                        multiply(P[c], minor2[a][b]), 1);
    const double sign = ((r + 1) % 2 == 0 ? 1.0 : -1.0) * orientation;
    for (double& x : det3.c) x *= sign;
    C[r] = std::move(det3);
  }
  return C;
}

Form dot(const Net4& C, const Net4& X) {
  Form sum = multiply(C[0], X[0]);
  for (int r = 1; r < 4; ++r) sum = combine(std::move(sum), multiply(C[r], X[r]), 1);
  return sum;
}

/// Halves f across `direction` at its middle (de Casteljau).
std::array<Form, 2> halve(const Form& f, int direction) {
  std::array<Form, 2> h{f, f};
  const int n = direction == 0 ? f.p : f.q, lines = direction == 0 ? f.q + 1 : f.p + 1;
  std::vector<double> row(static_cast<std::size_t>(n + 1));
  for (int l = 0; l < lines; ++l) {
    auto ref = [&](Form& g, int k) -> double& { return direction == 0 ? g.at(k, l) : g.at(l, k); };
    for (int k = 0; k <= n; ++k) row[static_cast<std::size_t>(k)] = direction == 0 ? f.at(k, l) : f.at(l, k);
    ref(h[0], 0) = row[0];
    ref(h[1], n) = row[static_cast<std::size_t>(n)];
    for (int r = 1; r <= n; ++r) {
      for (int k = 0; k + r <= n; ++k)
        row[static_cast<std::size_t>(k)] = 0.5 * (row[static_cast<std::size_t>(k)] + row[static_cast<std::size_t>(k + 1)]);
      ref(h[0], r) = row[0];
      ref(h[1], n - r) = row[static_cast<std::size_t>(n - r)];
    }
  }
  return h;
}

/// Is f >= −slack on its whole domain? A corner coefficient is the polynomial's value there: one below −slack
/// disproves it at once; otherwise pieces are halved (u and v in turn) until every coefficient is >= −slack.
bool provedNonNegative(const Form& f, double slack, int splits = 0) {
  const bool settled = std::all_of(f.c.begin(), f.c.end(), [&](double x) { return x >= -slack; });
  if (settled) return true;
  for (const double corner : {f.at(0, 0), f.at(f.p, 0), f.at(0, f.q), f.at(f.p, f.q)})
    if (corner < -slack) return false;
  if (splits >= kMaxSplits) return false;
  int direction = splits % 2;
  if ((direction == 0 ? f.p : f.q) == 0) direction = 1 - direction;
  if ((direction == 0 ? f.p : f.q) == 0) return false;
  const std::array<Form, 2> halves = halve(f, direction);
  return provedNonNegative(halves[0], slack, splits + 1) && provedNonNegative(halves[1], slack, splits + 1);
}

/// One patch's homogeneous net and its outward-oriented cross C (kept for the creases along its edges).
struct PatchForms {
  Net4 net, cross;
};

// Edges: 0: s = 0, 1: s = 1 (t runs along), 2: t = 0, 3: t = 1 (s runs along).
bool edgeAlongT(int e) { return e < 2; }

/// The 4-vector of forms restricted to edge e (univariate, degree (n, 0)).
Net4 restrictTo(const Net4& n, int e) {
  Net4 out;
  for (int r = 0; r < 4; ++r) {
    const Form& f = n[r];
    const int along = edgeAlongT(e) ? f.q : f.p;
    out[r] = zeroForm(along, 0);
    for (int k = 0; k <= along; ++k)
      out[r].at(k, 0) = edgeAlongT(e) ? f.at(e == 0 ? 0 : f.p, k) : f.at(k, e == 2 ? 0 : f.q);
    out[r].magnitude = f.magnitude;
  }
  return out;
}

/// The derivative across edge e pointing into the patch, restricted to the edge.
Net4 inwardDerivative(const Net4& net, int e) {
  const int direction = edgeAlongT(e) ? 0 : 1;
  Net4 d = restrictTo(derivative(net, direction), e);
  if (e == 1 || e == 3)
    for (Form& f : d)
      for (double& x : f.c) x = -x;
  return d;
}

Net4 reversed(Net4 n) {
  for (Form& f : n) std::reverse(f.c.begin(), f.c.end());
  return n;
}

/// The homogeneous control points along edge e.
std::vector<Eigen::Vector4d> edgePolygon(const RationalBezierPatch& p, int e) {
  std::vector<Eigen::Vector4d> out;
  const int n = edgeAlongT(e) ? p.degreeV : p.degreeU;
  for (int k = 0; k <= n; ++k)
    out.push_back(edgeAlongT(e) ? p.at(e == 0 ? 0 : p.degreeU, k) : p.at(k, e == 2 ? 0 : p.degreeV));
  return out;
}

bool collapsed(const std::vector<Eigen::Vector4d>& edge, double tol) {
  const Eigen::Vector3d first = edge.front().head<3>() / edge.front()[3];
  return std::all_of(edge.begin(), edge.end(), [&](const Eigen::Vector4d& x) { return (x.head<3>() / x[3] - first).norm() <= tol; });
}

/// Same rational curve: Euclidean points within tol and weights in one ratio, in order or reversed (0: no).
int sameCurve(const std::vector<Eigen::Vector4d>& a, const std::vector<Eigen::Vector4d>& b, double tol) {
  if (a.size() != b.size()) return 0;
  for (const int way : {1, -1}) {
    const double ratio = (way == 1 ? b.front()[3] : b.back()[3]) / a.front()[3];
    bool same = true;
    for (std::size_t k = 0; k < a.size() && same; ++k) {
      const Eigen::Vector4d& y = way == 1 ? b[k] : b[b.size() - 1 - k];
      same = (a[k].head<3>() / a[k][3] - y.head<3>() / y[3]).norm() <= tol &&
             std::abs(y[3] / a[k][3] - ratio) <= kEdgeMatch * ratio;
    }
    if (same) return way;
  }
  return 0;
}

int findRoot(std::vector<int>& parent, int x) {
  while (parent[static_cast<std::size_t>(x)] != x) x = parent[static_cast<std::size_t>(x)];
  return x;
}

void join(std::vector<int>& parent, int a, int b) { parent[static_cast<std::size_t>(findRoot(parent, a))] = findRoot(parent, b); }

ConvexityVerdict refuse(std::string reason) { return {false, std::move(reason)}; }

std::string edgeName(std::size_t patch, int e) {
  static const char* names[] = {"s = 0", "s = 1", "t = 0", "t = 1"};
  return "patch " + std::to_string(patch) + " edge " + names[e];
}

}  // namespace

ConvexityVerdict certifyConvexSolid(const std::vector<RationalBezierPatch>& patches, int orientation, double size) {
  if (patches.empty()) return refuse("no patches");
  std::vector<PatchForms> forms(patches.size());
  for (std::size_t k = 0; k < patches.size(); ++k) {
    const RationalBezierPatch& patch = patches[k];
    if (patch.degreeU > kMaxCertifiedDegree || patch.degreeV > kMaxCertifiedDegree)
      return refuse("patch " + std::to_string(k) + ": degree above " + std::to_string(kMaxCertifiedDegree));
    PatchForms& f = forms[k];
    f.net = netOf(patch);
    const Net4 Pu = derivative(f.net, 0), Pv = derivative(f.net, 1);
    f.cross = orientedCross(f.net, Pu, Pv, orientation);
    const Form L = dot(f.cross, derivative(Pu, 0)), M = dot(f.cross, derivative(Pu, 1)),
               N = dot(f.cross, derivative(Pv, 1));
    if (!provedNonNegative(L, kSlack * L.magnitude) || !provedNonNegative(N, kSlack * N.magnitude))
      return refuse("patch " + std::to_string(k) + " curves toward its outward normal somewhere");
    const Form det = combine(multiply(L, N), multiply(M, M), -1);
    if (!provedNonNegative(det, kSlack * det.magnitude))
      return refuse("patch " + std::to_string(k) + " is saddle-shaped somewhere");
  }

  // Every edge with length meets one other edge along the same polygon; the crease there folds inward. Edges are
  // sorted by the smaller x of their two ends (the same for a partner either way round), so each is compared
  // only with those within the matching distance of it.
  const double tol = kEdgeMatch * size;
  struct Edge {
    std::size_t patch;
    int side;
    std::vector<Eigen::Vector4d> polygon;
    double key;
  };
  std::vector<Edge> edges;
  for (std::size_t k = 0; k < patches.size(); ++k)
    for (int e = 0; e < 4; ++e) {
      std::vector<Eigen::Vector4d> polygon = edgePolygon(patches[k], e);
      if (collapsed(polygon, tol)) continue;  // a pole: no crease
      const double key = std::min(polygon.front()[0] / polygon.front()[3], polygon.back()[0] / polygon.back()[3]);
      edges.push_back({k, e, std::move(polygon), key});
    }
  std::sort(edges.begin(), edges.end(), [](const Edge& a, const Edge& b) { return a.key < b.key; });
  std::vector<int> parent(patches.size());
  std::iota(parent.begin(), parent.end(), 0);
  for (std::size_t n = 0; n < edges.size(); ++n) {
    const Edge& a = edges[n];
    int partners = 0;
    const auto nearby = [&](std::size_t m) { return std::abs(edges[m].key - a.key) <= tol; };
    std::size_t first = n;
    while (first > 0 && nearby(first - 1)) --first;
    for (std::size_t m = first; m < edges.size() && (m <= n || nearby(m)); ++m) {
      if (m == n) continue;
      const Edge& b = edges[m];
      const int way = sameCurve(a.polygon, b.polygon, tol);
      if (way == 0) continue;
      ++partners;
      const Net4 across = inwardDerivative(forms[b.patch].net, b.side);
      const Form crease = dot(restrictTo(forms[a.patch].cross, a.side), way == 1 ? across : reversed(across));
      if (!provedNonNegative(crease, kSlack * crease.magnitude))
        return refuse(edgeName(a.patch, a.side) + " folds outward where it meets " + edgeName(b.patch, b.side));
      join(parent, static_cast<int>(a.patch), static_cast<int>(b.patch));
    }
    if (partners != 1)
      return refuse(edgeName(a.patch, a.side) + (partners == 0 ? " meets no other edge along the same control polygon"
                                                               : " meets more than one other edge"));
  }
  for (std::size_t k = 1; k < patches.size(); ++k)
    if (findRoot(parent, static_cast<int>(k)) != findRoot(parent, 0)) return refuse("the surface is not connected");
  return {true, ""};
}

}  // namespace unidist::nurbs
