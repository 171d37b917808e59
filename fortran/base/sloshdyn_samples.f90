!> A uniformly sampled signal (a ground-motion record, in seconds or in the model's time): its
!> rules and its value between samples. Ground motion and the model's excitation share these,
!> so a record means the same thing in both.
module sloshdyn_samples
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use sloshdyn_kinds, only: wp, message_len
  use sloshdyn_status, only: SD_OK, SD_BAD_INPUT, check_real
  use sloshdyn_text, only: num2str
  implicit none
  private
  public :: check_samples, sampled_value

contains

  !> A step > 0 and at least 2 finite samples; `name` names the samples in messages.
  pure subroutine check_samples(name, samples, step, status, message)
    character(len=*), intent(in) :: name
    real(wp), intent(in) :: samples(:), step
    integer, intent(out) :: status
    character(len=message_len), intent(out) :: message
    integer :: i
    status = SD_OK
    message = ''
    call check_real('the time step of '//name, step, 0.0_wp, huge(1.0_wp), .true., .true., &
                    'it must be > 0', status, message)
    if (status == SD_OK .and. size(samples) < 2) then
      status = SD_BAD_INPUT
      message = name//' has '//num2str(size(samples))//' samples: it needs at least 2'
    end if
    if (status /= SD_OK) return
    ! the message (with the sample's number) only for the first sample that is not finite:
    ! formatting a number per sample cost more than a seismic run (issue 28)
    do i = 1, size(samples)
      if (ieee_is_finite(samples(i))) cycle
      call check_real(name//' sample '//num2str(i), samples(i), -huge(1.0_wp), huge(1.0_wp), &
                      .false., .false., 'samples must be finite', status, message)
      return
    end do
  end subroutine check_samples

  !> The signal at x: linear between the samples at x = (i - 1) step, 0 before the first and
  !> after the last (the ground is at rest outside the record).
  pure real(wp) function sampled_value(samples, step, x) result(value)
    real(wp), intent(in) :: samples(:), step, x
    real(wp) :: position
    integer :: i
    value = 0
    position = x/step
    if (position < 0 .or. position > size(samples) - 1) return
    i = min(int(position), size(samples) - 2)
    position = position - i
    value = (1 - position)*samples(i + 1) + position*samples(i + 2)
  end function sampled_value
end module sloshdyn_samples
