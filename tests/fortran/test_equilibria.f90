program test_equilibria
  use checks
  implicit none
  call finish()
end program test_equilibria
