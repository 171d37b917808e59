program test_motion
  use checks
  implicit none
  call finish()
end program test_motion
