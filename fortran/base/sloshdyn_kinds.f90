!> Working precision and the few constants every module shares.
module sloshdyn_kinds
  use, intrinsic :: iso_fortran_env, only: real64
  implicit none
  private
  public :: wp, pi, message_len

  integer, parameter :: wp = real64
  real(wp), parameter :: pi = 3.14159265358979323846264338327950288_wp
  !> Length of every status message handed back to a caller (fixed, so it crosses f2py).
  integer, parameter :: message_len = 512
end module sloshdyn_kinds
