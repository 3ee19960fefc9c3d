#include "tools/accuracy/cvode_peer.hpp"

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_config.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>

#include <cmath>

namespace gyrostab::tools::accuracy {
namespace {

// CVODE's messages would go to stderr mid-table; the solver reports its own failure instead.
void quiet(int, const char*, const char*, char*, void*) {}

}  // namespace

const char* cvode_method_name(CvodeMethod m) { return m == CvodeMethod::kBdf ? "cvode-bdf" : "cvode-adams"; }
const char* sundials_version() { return SUNDIALS_VERSION; }

int CvodeSolver::callback(double t, void* y, void* ydot, void* self) {
  auto* s = static_cast<CvodeSolver*>(self);
  s->rhs_(t, NV_DATA_S(static_cast<N_Vector>(y)), NV_DATA_S(static_cast<N_Vector>(ydot)), s->context_);
  return 0;
}

void CvodeSolver::fail(const char* what, int flag) {
  if (error_.empty()) error_ = std::string("CVODE ") + what + " failed (flag " + std::to_string(flag) + ")";
}

CvodeSolver::CvodeSolver(int n, CvodeMethod method, double tolerance, Rhs rhs, void* context)
    : n_(n), rhs_(rhs), context_(context) {
  init(method, tolerance);
}

void CvodeSolver::init(CvodeMethod method, double tolerance) {
  const int n = n_;
  SUNContext ctx = nullptr;
  if (int f = SUNContext_Create(nullptr, &ctx); f != 0) {
    fail("SUNContext_Create", f);
    return;
  }
  sunctx_ = ctx;
  N_Vector y = N_VNew_Serial(n, ctx);
  y_ = y;
  mem_ = CVodeCreate(method == CvodeMethod::kBdf ? CV_BDF : CV_ADAMS, ctx);
  if (y == nullptr || mem_ == nullptr) {
    fail("CVodeCreate", -1);
    return;
  }
  for (int i = 0; i < n; ++i) NV_Ith_S(y, i) = 0.0;
  CVodeSetErrHandlerFn(mem_, quiet, nullptr);
  const CVRhsFn f = [](realtype t, N_Vector yy, N_Vector yd, void* self) {
    return callback(t, yy, yd, self);
  };
  if (int flag = CVodeInit(mem_, f, 0.0, y); flag != CV_SUCCESS) return fail("CVodeInit", flag);
  if (int flag = CVodeSetUserData(mem_, this); flag != CV_SUCCESS) return fail("CVodeSetUserData", flag);
  if (int flag = CVodeSStolerances(mem_, tolerance, tolerance); flag != CV_SUCCESS) {
    return fail("CVodeSStolerances", flag);
  }
  CVodeSetMaxNumSteps(mem_, 1000000);
  if (method == CvodeMethod::kBdf) {
    SUNMatrix A = SUNDenseMatrix(n, n, ctx);
    SUNLinearSolver ls = SUNLinSol_Dense(y, A, ctx);
    matrix_ = A;
    linear_solver_ = ls;
    if (int flag = CVodeSetLinearSolver(mem_, ls, A); flag != CV_SUCCESS) return fail("CVodeSetLinearSolver", flag);
  } else {
    SUNNonlinearSolver nls = SUNNonlinSol_FixedPoint(y, 0, ctx);
    nonlinear_solver_ = nls;
    if (int flag = CVodeSetNonlinearSolver(mem_, nls); flag != CV_SUCCESS) {
      return fail("CVodeSetNonlinearSolver", flag);
    }
  }
}

CvodeSolver::~CvodeSolver() {
  if (mem_ != nullptr) CVodeFree(&mem_);
  if (nonlinear_solver_ != nullptr) SUNNonlinSolFree(static_cast<SUNNonlinearSolver>(nonlinear_solver_));
  if (linear_solver_ != nullptr) SUNLinSolFree(static_cast<SUNLinearSolver>(linear_solver_));
  if (matrix_ != nullptr) SUNMatDestroy(static_cast<SUNMatrix>(matrix_));
  if (y_ != nullptr) N_VDestroy(static_cast<N_Vector>(y_));
  if (sunctx_ != nullptr) {
    SUNContext ctx = static_cast<SUNContext>(sunctx_);
    SUNContext_Free(&ctx);
  }
}

bool CvodeSolver::advance(double t0, double t1, double* x) {
  if (!ok()) return false;
  N_Vector y = static_cast<N_Vector>(y_);
  for (int i = 0; i < n_; ++i) NV_Ith_S(y, i) = x[i];
  if (int flag = CVodeReInit(mem_, t0, y); flag != CV_SUCCESS) {
    fail("CVodeReInit", flag);
    return false;
  }
  if (int flag = CVodeSetStopTime(mem_, t1); flag != CV_SUCCESS) {
    fail("CVodeSetStopTime", flag);
    return false;
  }
  realtype t = t0;
  const int flag = CVode(mem_, t1, y, &t, CV_NORMAL);
  long n = 0;
  CVodeGetNumSteps(mem_, &n);  // counters restart with CVodeReInit
  total_steps_ += n;
  if (flag < 0) {
    fail("CVode", flag);
    return false;
  }
  for (int i = 0; i < n_; ++i) x[i] = NV_Ith_S(y, i);
  return true;
}

}  // namespace gyrostab::tools::accuracy
