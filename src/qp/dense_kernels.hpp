#pragma once
/// @file
/// Small dense kernels on raw column/row data, the inner loops of the QP solver.
///
/// Each kernel has a portable implementation and one for x86-64 CPUs with AVX2 and FMA, chosen
/// once at program start from the CPU's feature flags, so the library keeps the baseline
/// instruction set of its build. The two may differ in the last bits (summation order, fused
/// multiply-add); on one machine every call gives the same result for the same input.
/// None of them allocates.

namespace mjarm::qp::kernels {

/// out[i] = Σ_k A[i·lda + k]·x[k] for i < rows, k < cols (A row-major, or Aᵀ of column-major A).
/// @param A first element, rows of `cols` doubles spaced `lda` apart
/// @param x cols doubles
/// @param out rows doubles (must not alias A or x)
void row_dots(const double* A, int rows, int cols, int lda, const double* x, double* out) noexcept;

/// y = Σ_k x[k]·A[k·lda + 0..rows) (A column-major rows×cols: y = A·x).
/// @param y rows doubles, overwritten (must not alias A or x)
void columns_times(const double* A, int rows, int cols, int lda, const double* x,
                   double* y) noexcept;

/// Plane rotation of two arrays: a ← c·a + s·b, b ← c·b − s·a (len entries each).
void rotate(double* a, double* b, int len, double c, double s) noexcept;

/// A chain of plane rotations on adjacent columns of a column-major matrix A (rows × ·, lda).
/// Rotation t (0 ≤ t < count) acts on the column pair (k_t, k_t + 1) as
///     col k_t ← c[t]·col k_t + s[t]·col k_t+1,   col k_t+1 ← c[t]·col k_t+1 − s[t]·col k_t,
/// with k_t = first + t (ascending) or k_t = first + count − 1 − t (descending), applied in
/// order t = 0, 1, …; each column is read and written once per block of rows.
void rotate_columns(double* A, int rows, int lda, int first, int count, const double* c,
                    const double* s, bool descending) noexcept;

/// Householder reflection of `count` adjacent columns V = A[:, first, first + count) of a
/// column-major matrix A (rows × ·, lda), from the right: V ← V·(I − tau·v·vᵀ), computed as
/// y = V·v, V ← V − tau·y·vᵀ, one block of rows at a time.
/// @param v count doubles
void reflect_columns(double* A, int rows, int lda, int first, int count, const double* v,
                     double tau) noexcept;

/// Row products and scaled margins of two-sided rows lo ≤ A·x ≤ hi (A column-major,
/// rows × cols, columns spaced lda apart):
///     cx[i] = A_i·x,   margin[i] = min(cx[i] − lo[i], hi[i] − cx[i])·scale[i],
/// which also finds the row with the smallest margin[i] + skip[i] (skip[i] = 0 to consider row
/// i, +∞ to ignore it); ties go to the lowest index, NaN is never the smallest.
/// @return that row, or −1 if no considered row has a margin below +∞
int column_margins(const double* A, int rows, int cols, int lda, const double* x,
                   const double* lo, const double* hi, const double* scale, const double* skip,
                   double* cx, double* margin) noexcept;

/// The first entries i of v (len entries) with v[i] ≤ t, in increasing order: writes their
/// indices to idx and stops once there are more than max_count of them (NaN never qualifies).
/// @param idx room for max_count + 1 indices
/// @return how many were found, at most max_count + 1 (which means "more than max_count")
int select_at_most(const double* v, int len, double t, int max_count, int* idx) noexcept;

/// out[k] = A_{idx[k]}·x for k < count: products of selected rows of a row-major A (rows of
/// `cols` doubles spaced lda apart) with x, several rows at a time.
void indexed_row_dots(const double* A, int cols, int lda, const int* idx, int count,
                      const double* x, double* out) noexcept;

/// Σ_k a[k]·b[k] over len entries.
double dot(const double* a, const double* b, int len) noexcept;

/// y ← y + alpha·x over len entries.
void axpy(double alpha, const double* x, double* y, int len) noexcept;

/// Whether the AVX2/FMA implementations are in use.
bool using_avx2() noexcept;

/// Selects the portable implementations even where AVX2/FMA exist (on = true), or the best
/// available again (on = false). For tests that cover both paths; not meant to be switched
/// while another thread runs a kernel.
void force_portable(bool on) noexcept;

}  // namespace mjarm::qp::kernels
