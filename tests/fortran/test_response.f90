!> The slow-flow frequency response's input checks: every bad setting is reported by name, also
!> when the result tables are wrong too (the first failure wins; a former operator-precedence
!> error let the table-shape message replace it).
program test_response
  use sloshdyn_kinds, only: wp, pi, message_len
  use sloshdyn_status, only: SD_BAD_INPUT
  use sloshdyn_model, only: model_t, model_from_arrays
  use sloshdyn_excitation, only: PARAMETER_RHO
  use sloshdyn_response, only: response_options, frequency_response
  use sloshdyn_tables, only: POINT_ROWS, SPECIAL_ROWS
  use checks, only: check_true, finish
  implicit none

  type(model_t) :: model
  type(response_options) :: options
  real(wp) :: table(POINT_ROWS, 10), special(SPECIAL_ROWS, 5), wrong_special(3, 5)
  integer :: status, n_points, n_special
  logical :: complete
  character(len=message_len) :: message

  call model_from_arrays([1.5_wp, 0.5_wp, 1.804897259_wp, pi/4, 10.0_wp, 0.001_wp, 0.1_wp, &
                          0.00075_wp, 0.5_wp, 0.0_wp], [6, 2], model, status, message)
  options%n_scan = 0
  call frequency_response(model, .true., PARAMETER_RHO, 0.49_wp, 0.53_wp, options, table, &
                          n_points, wrong_special, n_special, complete, status, message)
  call check_true('n_scan = 0 is named even with a wrong special table: '//trim(message), &
                  status == SD_BAD_INPUT .and. index(message, 'n_scan = 0') > 0 .and. &
                  .not. complete .and. n_points == 0)
  options = response_options()
  call frequency_response(model, .true., PARAMETER_RHO, 0.49_wp, 0.53_wp, options, table, &
                          n_points, wrong_special, n_special, complete, status, message)
  call check_true('a wrong special table is reported: '//trim(message), &
                  status == SD_BAD_INPUT .and. index(message, 'rows') > 0)
  options%amplitude_min = 2
  call frequency_response(model, .true., PARAMETER_RHO, 0.49_wp, 0.53_wp, options, table, &
                          n_points, special, n_special, complete, status, message)
  call check_true('amplitude_min > amplitude_max is named: '//trim(message), &
                  status == SD_BAD_INPUT .and. index(message, 'amplitude_min = 2') > 0)
  call finish()
end program test_response
