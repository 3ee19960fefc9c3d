// The no-heap rule made a link error (docs/architecture.md, allocation-free rules): the target link wraps
// malloc, free, calloc, realloc, their newlib-reentrant forms and _sbrk (-Wl,--wrap=...,
// tools/cross/build-firmware-arm), so every reference to them — from our code, libstdc++ or newlib — lands on
// the __wrap_ functions below; and every form of operator new is defined here. All of them call
// gyrostab_firmware_heap_use_is_forbidden(), which is defined nowhere.
// With -ffunction-sections and --gc-sections an unreachable one is discarded with its reference, so the link
// succeeds exactly when no allocation is reachable, and otherwise fails with
//   undefined reference to `gyrostab_firmware_heap_use_is_forbidden'
// naming the allocating function. The cross build proves the failure with a file that calls new.
//
// operator delete is the exception: every class with a virtual destructor references it from its vtable
// (the deleting destructor) even if nothing is ever allocated; since new cannot link, delete can never get
// a heap pointer, so it only traps on a non-null pointer instead of failing the link.
#include <cstddef>
#include <new>

extern "C" [[noreturn]] void gyrostab_firmware_heap_use_is_forbidden();  // deliberately never defined

struct _reent;  // newlib's reentrancy context

extern "C" {
void* __wrap_malloc(std::size_t) {
  gyrostab_firmware_heap_use_is_forbidden();
}
void* __wrap_calloc(std::size_t, std::size_t) {
  gyrostab_firmware_heap_use_is_forbidden();
}
void* __wrap_realloc(void*, std::size_t) {
  gyrostab_firmware_heap_use_is_forbidden();
}
void __wrap_free(void*) {
  gyrostab_firmware_heap_use_is_forbidden();
}
void* __wrap__malloc_r(_reent*, std::size_t) {
  gyrostab_firmware_heap_use_is_forbidden();
}
void* __wrap__calloc_r(_reent*, std::size_t, std::size_t) {
  gyrostab_firmware_heap_use_is_forbidden();
}
void* __wrap__realloc_r(_reent*, void*, std::size_t) {
  gyrostab_firmware_heap_use_is_forbidden();
}
void __wrap__free_r(_reent*, void*) {
  gyrostab_firmware_heap_use_is_forbidden();
}
void* __wrap__sbrk(std::ptrdiff_t) {
  gyrostab_firmware_heap_use_is_forbidden();
}
}

void* operator new(std::size_t) {
  gyrostab_firmware_heap_use_is_forbidden();
}
void* operator new[](std::size_t) {
  gyrostab_firmware_heap_use_is_forbidden();
}
void* operator new(std::size_t, const std::nothrow_t&) noexcept {
  gyrostab_firmware_heap_use_is_forbidden();
}
void* operator new[](std::size_t, const std::nothrow_t&) noexcept {
  gyrostab_firmware_heap_use_is_forbidden();
}
void* operator new(std::size_t, std::align_val_t) {
  gyrostab_firmware_heap_use_is_forbidden();
}
void* operator new[](std::size_t, std::align_val_t) {
  gyrostab_firmware_heap_use_is_forbidden();
}
void* operator new(std::size_t, std::align_val_t, const std::nothrow_t&) noexcept {
  gyrostab_firmware_heap_use_is_forbidden();
}
void* operator new[](std::size_t, std::align_val_t, const std::nothrow_t&) noexcept {
  gyrostab_firmware_heap_use_is_forbidden();
}

namespace {
void trap_unless_null(void* p) {
  if (p != nullptr) __builtin_trap();
}
}  // namespace

void operator delete(void* p) noexcept {
  trap_unless_null(p);
}
void operator delete[](void* p) noexcept {
  trap_unless_null(p);
}
void operator delete(void* p, std::size_t) noexcept {
  trap_unless_null(p);
}
void operator delete[](void* p, std::size_t) noexcept {
  trap_unless_null(p);
}
void operator delete(void* p, std::align_val_t) noexcept {
  trap_unless_null(p);
}
void operator delete[](void* p, std::align_val_t) noexcept {
  trap_unless_null(p);
}
void operator delete(void* p, std::size_t, std::align_val_t) noexcept {
  trap_unless_null(p);
}
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept {
  trap_unless_null(p);
}
