program test_linear
  use checks
  implicit none
  call finish()
end program test_linear
