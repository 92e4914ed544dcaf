// Zhang's planar calibration from one view: normalised DLT homography, closed-form focal
// length and pose from it, then Levenberg-Marquardt over all 12 parameters. World
// coordinates are handled in millimetres inside so that pose and angles are similarly scaled.
#include "vt/acquisition/calibration.hpp"

#include <cmath>
#include <tuple>

#include <Eigen/Dense>
#include <nlohmann/json.hpp>

#include "vt/core/error.hpp"

namespace vt::acq {
namespace {

constexpr int kIntrinsics = 6;  // fx fy cx cy k1 k2
constexpr int kPose = 6;        // r0 r1 r2 t0 t1 t2(mm)
constexpr const char* kParamNames[kIntrinsics] = {"fx", "fy", "cx", "cy", "k1", "k2"};
// One view's priors: the principal point within 2 % of the image's larger side of the centre
// (one standard deviation), k2 within 0.05 of 0; the click noise the first fit weighs them with.
constexpr double kPrincipalPointSigma = 0.02;
constexpr double kK2Sigma = 0.05;
constexpr double kNominalClick_px = 0.3;

// Parameter vector: the intrinsics, then one pose per view; view 0 is the object plane.
CameraModel toCamera(const Eigen::VectorXd& p, std::size_t view) {
  CameraModel c;
  c.fx = p[0], c.fy = p[1], c.cx = p[2], c.cy = p[3], c.k1 = p[4], c.k2 = p[5];
  const Eigen::Index o = kIntrinsics + Eigen::Index(view) * kPose;
  c.rvec = {p[o], p[o + 1], p[o + 2]};
  c.t_m = {p[o + 3] * 1e-3, p[o + 4] * 1e-3, p[o + 5] * 1e-3};
  return c;
}

void putPose(Eigen::VectorXd& p, std::size_t view, const CameraModel& c) {
  const Eigen::Index o = kIntrinsics + Eigen::Index(view) * kPose;
  p.segment(o, kPose) << c.rvec[0], c.rvec[1], c.rvec[2], c.t_m[0] * 1e3, c.t_m[1] * 1e3, c.t_m[2] * 1e3;
}

// A Gaussian prior on one parameter, as a residual row weight * (p - mean): whitened priors use
// weight = noise / sigma (noise = the points' residual std per coordinate), so that the row counts
// as one measurement of the parameter with standard deviation sigma.
struct Prior {
  Eigen::Index index;
  double mean;
  double sigma;   // 0: a fixed weight (the weak principal-point pull of several views)
  double weight;
};

struct Problem {
  std::span<const std::span<const Correspondence>> views;
  std::vector<Prior> priors;
  std::vector<Eigen::Index> free;  // indices of the parameters the fit moves

  Eigen::Index pointResiduals() const {
    Eigen::Index n = 0;
    for (const auto& v : views) n += Eigen::Index(v.size()) * 2;
    return n;
  }
  Eigen::Index residualCount() const { return pointResiduals() + Eigen::Index(priors.size()); }

  /// Re-weights the whitened priors for a residual std of `noise_px` per coordinate.
  void setNoise(double noise_px) {
    for (Prior& prior : priors)
      if (prior.sigma > 0) prior.weight = noise_px / prior.sigma;
  }

  Eigen::VectorXd residuals(const Eigen::VectorXd& p) const {
    Eigen::VectorXd r(residualCount());
    Eigen::Index k = 0;
    for (std::size_t view = 0; view < views.size(); ++view) {
      const CameraModel cam = toCamera(p, view);
      for (const Correspondence& c : views[view]) {
        const glm::dvec2 q = cam.project(c.x_m, c.y_m);
        r[k++] = q.x - c.u_px;
        r[k++] = q.y - c.v_px;
      }
    }
    for (const Prior& prior : priors) r[k++] = prior.weight * (p[prior.index] - prior.mean);
    return r;
  }

  Eigen::MatrixXd jacobian(const Eigen::VectorXd& p) const {
    Eigen::MatrixXd J(residualCount(), Eigen::Index(free.size()));
    for (std::size_t k = 0; k < free.size(); ++k) {
      const Eigen::Index i = free[k];
      const double h = 1e-6 * std::max(1.0, std::abs(p[i]));
      Eigen::VectorXd a = p, b = p;
      a[i] += h;
      b[i] -= h;
      J.col(Eigen::Index(k)) = (residuals(a) - residuals(b)) / (2 * h);
    }
    return J;
  }

  /// Levenberg-Marquardt from `p` until the cost stops falling; returns the iterations used
  /// and whether it converged.
  std::pair<int, bool> minimise(Eigen::VectorXd& p) const {
    Eigen::VectorXd r = residuals(p);
    double cost = r.squaredNorm();
    double lambda = 1e-3;
    const auto nFree = Eigen::Index(free.size());
    for (int iter = 0; iter < 200; ++iter) {
      const Eigen::MatrixXd J = jacobian(p);
      const Eigen::MatrixXd JtJ = J.transpose() * J;
      const Eigen::VectorXd g = J.transpose() * r;
      bool improved = false, converged = false;
      while (lambda < 1e12) {
        Eigen::MatrixXd Aug = JtJ;
        Aug.diagonal() += lambda * (JtJ.diagonal().array() + 1e-9).matrix();
        const Eigen::VectorXd step = Aug.ldlt().solve(-g);
        Eigen::VectorXd candidate = p;
        for (Eigen::Index k = 0; k < nFree; ++k) candidate[free[std::size_t(k)]] += step[k];
        const Eigen::VectorXd rc = residuals(candidate);
        const double costC = rc.squaredNorm();
        if (std::isfinite(costC) && costC < cost) {
          const double gain = cost - costC;
          p = candidate, r = rc;
          lambda = std::max(lambda * 0.3, 1e-12);
          improved = true;
          converged = gain < 1e-12 * (1 + cost) || step.norm() < 1e-12 * (1 + p.norm());
          cost = costC;
          break;
        }
        lambda *= 10;
      }
      if (!improved) return {iter + 1, true};  // no direction lowers the cost: a (local) minimum
      if (converged) return {iter + 1, true};
    }
    return {200, false};
  }

  /// The points' residual std per coordinate at `p` (degrees of freedom: the points less the
  /// free parameters the priors do not pin; at least one).
  double noise(const Eigen::VectorXd& p) const {
    const Eigen::Index dof = std::max<Eigen::Index>(1, pointResiduals() - Eigen::Index(free.size()) + Eigen::Index(priors.size()));
    return std::sqrt(residuals(p).head(pointResiduals()).squaredNorm() / double(dof));
  }
};

// Hartley normalisation: centroid to the origin, mean distance sqrt(2).
Eigen::Matrix3d normaliser(const std::vector<Eigen::Vector2d>& pts) {
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& q : pts) mean += q;
  mean /= double(pts.size());
  double dist = 0;
  for (const auto& q : pts) dist += (q - mean).norm();
  dist /= double(pts.size());
  const double s = dist > 0 ? std::sqrt(2.0) / dist : 1.0;
  Eigen::Matrix3d T;
  T << s, 0, -s * mean.x(), 0, s, -s * mean.y(), 0, 0, 1;
  return T;
}

// Homography from world (mm, on Z = 0) to pixels by the normalised DLT.
Eigen::Matrix3d homographyDlt(std::span<const Correspondence> points) {
  std::vector<Eigen::Vector2d> world, pixel;
  for (const auto& c : points) {
    world.emplace_back(c.x_m * 1e3, c.y_m * 1e3);
    pixel.emplace_back(c.u_px, c.v_px);
  }
  const Eigen::Matrix3d Tw = normaliser(world), Tp = normaliser(pixel);
  Eigen::MatrixXd A(2 * points.size(), 9);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d X = Tw * world[i].homogeneous();
    const Eigen::Vector3d x = Tp * pixel[i].homogeneous();
    const auto r = Eigen::Index(2 * i);
    A.row(r) << X.x(), X.y(), 1, 0, 0, 0, -x.x() * X.x(), -x.x() * X.y(), -x.x();
    A.row(r + 1) << 0, 0, 0, X.x(), X.y(), 1, -x.y() * X.x(), -x.y() * X.y(), -x.y();
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeFullV);
  const Eigen::VectorXd h = svd.matrixV().col(8);
  Eigen::Matrix3d Hn;
  Hn << h[0], h[1], h[2], h[3], h[4], h[5], h[6], h[7], h[8];
  return Tp.inverse() * Hn * Tw;
}

// Focal length (fx = fy) and pose from the homography, principal point assumed at (cx, cy).
CameraModel initialCamera(const Eigen::Matrix3d& H, double cx, double cy, double fallbackFocal) {
  Eigen::Matrix3d Tc;
  Tc << 1, 0, -cx, 0, 1, -cy, 0, 0, 1;
  const Eigen::Matrix3d A = Tc * H;  // = diag(f, f, 1) [r1 r2 t] up to scale
  const Eigen::Vector3d a1 = A.col(0), a2 = A.col(1);
  // r1.r2 = 0 and |r1| = |r2| are linear in u = 1/f^2: c_i u + d_i = 0.
  const double c1 = a1.x() * a2.x() + a1.y() * a2.y(), d1 = a1.z() * a2.z();
  const double c2 = a1.x() * a1.x() + a1.y() * a1.y() - a2.x() * a2.x() - a2.y() * a2.y();
  const double d2 = a1.z() * a1.z() - a2.z() * a2.z();
  const double den = c1 * c1 + c2 * c2;
  const double u = den > 0 ? -(c1 * d1 + c2 * d2) / den : -1.0;
  double f = u > 0 ? 1.0 / std::sqrt(u) : fallbackFocal;
  if (!std::isfinite(f) || f < 0.05 * fallbackFocal || f > 50 * fallbackFocal) f = fallbackFocal;

  const Eigen::Matrix3d Kinv = Eigen::Vector3d(1 / f, 1 / f, 1).asDiagonal();
  Eigen::Matrix3d B = Kinv * A;
  double lambda = 1.0 / B.col(0).norm();
  if (B(2, 2) * lambda < 0) lambda = -lambda;  // the plane lies in front of the camera
  const Eigen::Vector3d r1 = lambda * B.col(0), r2 = lambda * B.col(1), t = lambda * B.col(2);
  Eigen::Matrix3d R;
  R << r1, r2, r1.cross(r2);
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(R, Eigen::ComputeFullU | Eigen::ComputeFullV);
  R = svd.matrixU() * svd.matrixV().transpose();  // nearest rotation
  if (R.determinant() < 0) R = -R;

  CameraModel cam;
  cam.fx = cam.fy = f;
  cam.cx = cx;
  cam.cy = cy;
  std::array<double, 9> r{};
  for (int i = 0; i < 9; ++i) r[std::size_t(i)] = R(i / 3, i % 3);
  cam.rvec = vectorFromRotation(r);
  cam.t_m = {t.x() * 1e-3, t.y() * 1e-3, t.z() * 1e-3};
  return cam;
}

void checkLayout(std::span<const Correspondence> points, const std::string& source) {
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& c : points) mean += Eigen::Vector2d(c.x_m, c.y_m);
  mean /= double(points.size());
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (const auto& c : points) {
    const Eigen::Vector2d d = Eigen::Vector2d(c.x_m, c.y_m) - mean;
    cov += d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov / double(points.size()));
  // The smaller spread below 1 mm means the points are (nearly) on one line: no homography.
  if (eig.eigenvalues()[0] < 1e-6) fail(source, ": calibration points are collinear or coincident (need a 2-D spread)");
}

// Reprojection errors of the result's camera on the marked points.
void fillErrors(CalibrationResult& result, std::span<const Correspondence> points) {
  double sum = 0;
  for (const auto& c : points) {
    const glm::dvec2 q = result.camera.project(c.x_m, c.y_m);
    const double e = std::hypot(q.x - c.u_px, q.y - c.v_px);
    result.errors_px.push_back(e);
    sum += e * e;
    result.maxError_px = std::max(result.maxError_px, e);
  }
  result.rmsError_px = points.empty() ? 0.0 : std::sqrt(sum / double(points.size()));
}

}  // namespace

std::array<double, 9> rotationFromVector(const std::array<double, 3>& rvec) noexcept {
  const Eigen::Vector3d v(rvec[0], rvec[1], rvec[2]);
  const double angle = v.norm();
  const Eigen::Matrix3d R =
      angle < 1e-15 ? Eigen::Matrix3d::Identity() : Eigen::AngleAxisd(angle, v / angle).toRotationMatrix();
  std::array<double, 9> out{};
  for (int i = 0; i < 9; ++i) out[std::size_t(i)] = R(i / 3, i % 3);
  return out;
}

std::array<double, 3> vectorFromRotation(const std::array<double, 9>& r) noexcept {
  Eigen::Matrix3d R;
  for (int i = 0; i < 9; ++i) R(i / 3, i % 3) = r[std::size_t(i)];
  const Eigen::AngleAxisd aa(R);
  const Eigen::Vector3d v = aa.axis() * aa.angle();
  return {v.x(), v.y(), v.z()};
}

glm::dvec2 CameraModel::distort(glm::dvec2 n) const noexcept {
  const double r2 = n.x * n.x + n.y * n.y;
  const double d = 1 + r2 * (k1 + r2 * (k2 + r2 * k3));
  const double x = n.x * d + 2 * p1 * n.x * n.y + p2 * (r2 + 2 * n.x * n.x);
  const double y = n.y * d + p1 * (r2 + 2 * n.y * n.y) + 2 * p2 * n.x * n.y;
  return {fx * x + cx, fy * y + cy};
}

glm::dvec2 CameraModel::project(double x_m, double y_m, double z_m) const noexcept {
  const auto R = rotationFromVector(rvec);
  const double X = R[0] * x_m + R[1] * y_m + R[2] * z_m + t_m[0];
  const double Y = R[3] * x_m + R[4] * y_m + R[5] * z_m + t_m[1];
  const double Z = R[6] * x_m + R[7] * y_m + R[8] * z_m + t_m[2];
  return distort({X / Z, Y / Z});
}

glm::dvec2 CameraModel::planePoint(glm::dvec2 pixel) const noexcept {
  // Undistort by fixed-point iteration (distortion is mild inside the photo).
  const double xd = (pixel.x - cx) / fx, yd = (pixel.y - cy) / fy;
  double x = xd, y = yd;
  for (int i = 0; i < 8; ++i) {
    const double r2 = x * x + y * y, d = 1 + r2 * (k1 + r2 * (k2 + r2 * k3));
    x = (xd - 2 * p1 * x * y - p2 * (r2 + 2 * x * x)) / d;
    y = (yd - p1 * (r2 + 2 * y * y) - 2 * p2 * x * y) / d;
  }
  // The ray eye + s * R^T (x, y, 1) meets Z = 0; eye = -R^T t.
  const auto R = rotationFromVector(rvec);
  const glm::dvec3 dir(R[0] * x + R[3] * y + R[6], R[1] * x + R[4] * y + R[7], R[2] * x + R[5] * y + R[8]);
  const glm::dvec3 eye(-(R[0] * t_m[0] + R[3] * t_m[1] + R[6] * t_m[2]), -(R[1] * t_m[0] + R[4] * t_m[1] + R[7] * t_m[2]),
                       -(R[2] * t_m[0] + R[5] * t_m[1] + R[8] * t_m[2]));
  const double s = -eye.z / dir.z;
  return {eye.x + s * dir.x, eye.y + s * dir.y};
}

CalibrationResult calibrateCamera(std::span<const Correspondence> points, int imageWidth, int imageHeight,
                                  const CalibrationPriors& priors, const std::string& source,
                                  std::span<const std::vector<Correspondence>> extraViews) {
  if (points.size() < 8) fail(source, ": too few calibration points: ", points.size(), " (need at least 8)");
  if (imageWidth < 1 || imageHeight < 1) fail(source, ": photo has no pixels");
  checkLayout(points, source);
  std::vector<std::span<const Correspondence>> views{points};
  for (std::size_t i = 0; i < extraViews.size(); ++i) {
    const std::string where = str(source, " view ", i + 1);
    if (extraViews[i].size() < 8) fail(where, ": too few calibration points: ", extraViews[i].size(), " (need at least 8)");
    checkLayout(extraViews[i], where);
    views.emplace_back(extraViews[i]);
  }
  const double cx0 = imageWidth / 2.0, cy0 = imageHeight / 2.0;
  Problem problem{views, {}, {}};
  CalibrationResult result;
  result.views = int(views.size());
  // One plane cannot separate the principal point from the pose, nor k2 from k1 (Zhang): left
  // free they wander (35 px, k2 -0.37 on a synthetic scan) and pull fx with them; held fixed they
  // bias fx (1099-1139 px against 1082) while its standard error claims far less. So one view
  // fits every intrinsic with priors on what it cannot tell apart (what cameras are made to:
  // the principal point near the centre, mild k2), and the covariance carries their uncertainty
  // into fx. Several views determine them; only a weak pull keeps LM well posed.
  const bool oneView = views.size() == 1;
  if (oneView) {
    const double sigmaCentre = kPrincipalPointSigma * std::max(imageWidth, imageHeight);
    problem.priors.push_back({2, cx0, sigmaCentre, 0.0});
    problem.priors.push_back({3, cy0, sigmaCentre, 0.0});
    problem.priors.push_back({5, 0.0, kK2Sigma, 0.0});
  } else {
    problem.priors.push_back({2, cx0, 0.0, priors.principalPointWeight});
    problem.priors.push_back({3, cy0, 0.0, priors.principalPointWeight});
  }
  if (priors.focal_px) {
    for (const Eigen::Index i : {0, 1}) problem.priors.push_back({i, (*priors.focal_px)[0], (*priors.focal_px)[1], 0.0});
  }
  for (const Prior& prior : problem.priors) {
    if (prior.sigma > 0) result.priors[std::size_t(prior.index)] = {prior.mean, prior.sigma};
  }
  for (Eigen::Index i = 0; i < kIntrinsics + Eigen::Index(views.size()) * kPose; ++i) problem.free.push_back(i);

  Eigen::VectorXd p = Eigen::VectorXd::Zero(kIntrinsics + Eigen::Index(views.size()) * kPose);
  double focalSum = 0;
  for (std::size_t v = 0; v < views.size(); ++v) {
    const CameraModel init = initialCamera(homographyDlt(views[v]), cx0, cy0, double(std::max(imageWidth, imageHeight)));
    putPose(p, v, init);
    focalSum += init.fx;
  }
  const double focal0 = priors.focal_px ? (*priors.focal_px)[0] : focalSum / double(views.size());
  p.head(kIntrinsics) << focal0, focal0, cx0, cy0, 0, 0;
  // The priors weigh against the points' own scatter, known only after a fit: fit with a nominal
  // click noise, measure the scatter, and fit again with the priors weighted by it.
  problem.setNoise(kNominalClick_px);
  std::tie(result.iterations, result.converged) = problem.minimise(p);
  const double noise = problem.noise(p);
  if (std::isfinite(noise) && noise > 0) {
    problem.setNoise(noise);
    const auto [iterations, converged] = problem.minimise(p);
    result.iterations += iterations;
    result.converged = converged;
  }
  result.camera = toCamera(p, 0);
  fillErrors(result, points);
  if (!std::isfinite(result.rmsError_px) || result.camera.t_m[2] <= 0) {
    fail(source, ": camera calibration did not converge (check that pixel and robot coordinates match)");
  }
  // Standard errors from the covariance s^2 (J^T J)^-1, s^2 = the points' residual variance per
  // coordinate; a whitened prior row weighs as one measurement with its own sigma.
  const double s = problem.noise(p);
  problem.setNoise(s);
  const Eigen::MatrixXd J = problem.jacobian(p);
  const Eigen::MatrixXd cov = (J.transpose() * J).completeOrthogonalDecomposition().pseudoInverse() * (s * s);
  for (Eigen::Index i = 0; i < kIntrinsics; ++i) result.std[std::size_t(i)] = std::sqrt(std::max(0.0, cov(i, i)));
  return result;
}

CalibrationResult givenCamera(const KnownCamera& k, std::span<const Correspondence> points) {
  CalibrationResult result;
  result.given = true;
  result.converged = true;
  CameraModel& c = result.camera;
  c.fx = k.fx, c.fy = k.fy, c.cx = k.cx, c.cy = k.cy;
  c.k1 = k.distortion[0], c.k2 = k.distortion[1], c.p1 = k.distortion[2], c.p2 = k.distortion[3], c.k3 = k.distortion[4];
  c.rvec = k.rvec, c.t_m = k.t_m;
  fillErrors(result, points);
  return result;
}

bool CalibrationResult::reliable(int parameter) const noexcept {
  const auto i = std::size_t(parameter);
  // Determined when the standard error is small against what the parameter changes: 0.5 %
  // of the focal length, 2 px of principal point, distortion to within 0.01 (about 1 px at
  // the edge of a 640 px photo for k1; k2 weighs r^4).
  const double limit[kIntrinsics] = {0.005 * camera.fx, 0.005 * camera.fy, 2.0, 2.0, 0.01, 0.01};
  return std::isfinite(std[i]) && std[i] <= limit[i];
}

bool CalibrationResult::fromPrior(int parameter) const noexcept {
  const auto& prior = priors[std::size_t(parameter)];
  // The data narrowed the prior by less than 30 %: the value says more about the prior than the photo.
  return prior && std[std::size_t(parameter)] > 0.7 * (*prior)[1];
}

std::string calibrationReportJson(const CalibrationResult& result, std::span<const Correspondence> points) {
  const CameraModel& c = result.camera;
  nlohmann::json doc;
  doc["model"] = "pinhole + radial (k1, k2) and, for a given camera, p1, p2, k3; OpenCV conventions; world = robot "
                 "base frame in metres, Z = 0 on the object";
  doc["intrinsics"] = {{"fx", c.fx}, {"fy", c.fy}, {"cx", c.cx}, {"cy", c.cy}};
  doc["distortion"] = {{"k1", c.k1}, {"k2", c.k2}, {"p1", c.p1}, {"p2", c.p2}, {"k3", c.k3}};
  doc["source"] = result.given ? "scan.json 'camera' (calibrated elsewhere; not fitted here)" : "fitted to the marked points";
  doc["views"] = result.views;
  const double values[kIntrinsics] = {c.fx, c.fy, c.cx, c.cy, c.k1, c.k2};
  nlohmann::json params;
  for (int i = 0; i < kIntrinsics; ++i) {
    const auto& prior = result.priors[std::size_t(i)];
    if (result.given) {  // calibrated elsewhere: nothing here says how well
      params[kParamNames[i]] = {{"value", values[i]}, {"status", "given"}, {"std", nullptr}, {"prior", nullptr}, {"reliable", nullptr}};
      continue;
    }
    params[kParamNames[i]] = {{"value", values[i]},
                              {"status", result.fromPrior(i) ? "prior" : "fitted"},
                              {"std", result.std[std::size_t(i)]},
                              {"prior", prior ? nlohmann::json{{"mean", (*prior)[0]}, {"std", (*prior)[1]}} : nlohmann::json(nullptr)},
                              {"reliable", result.reliable(i)}};
  }
  doc["parameters"] = params;
  doc["reliability_note"] =
      "std = standard error from the fit covariance, priors included; status 'prior': the data narrowed the prior by "
      "less than 30 %, so the value is mostly the prior's; reliable: std below 0.5 % of f (fx, fy), 2 px (cx, cy), "
      "0.01 (k1, k2)";
  doc["rvec"] = c.rvec;
  doc["t_m"] = c.t_m;
  doc["reprojection_rms_px"] = result.rmsError_px;
  doc["reprojection_max_px"] = result.maxError_px;
  doc["iterations"] = result.iterations;
  doc["converged"] = result.converged;
  nlohmann::json rows = nlohmann::json::array();
  for (std::size_t i = 0; i < points.size() && i < result.errors_px.size(); ++i) {
    const glm::dvec2 q = c.project(points[i].x_m, points[i].y_m);
    rows.push_back({{"x_m", points[i].x_m}, {"y_m", points[i].y_m}, {"u_px", points[i].u_px},
                    {"v_px", points[i].v_px}, {"projected", {q.x, q.y}}, {"error_px", result.errors_px[i]}});
  }
  doc["points"] = rows;
  return doc.dump(2) + "\n";
}

}  // namespace vt::acq
