program test_model
  use checks
  implicit none
  call finish()
end program test_model
