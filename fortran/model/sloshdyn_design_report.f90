!> The design check's two tables for a checker (docs/design.md, "Checks and hand calculation"):
!>
!> - the checks ('design_checks'): one row per check, each code's demand against its capacity
!>   with the clause, the unit, the ratio demand/capacity and the verdict (OK, NOT OK, or INFO
!>   for a value that has no capacity);
!> - the hand calculation ('design_calc'): one row per formula in the order a checker reads it,
!>   with the formula, the numbers put in (5 significant digits), the value (full precision), its
!>   unit and its clause.
!>
!> The code modules fill a design_report_t as they compute (step returns the value it records,
!> so each formula is typed once, beside its clause); report_lines gives the CSV text that the
!> executable writes and the bridge hands to Python (one source for both front doors).
module sloshdyn_design_report
  use sloshdyn_kinds, only: wp
  use sloshdyn_text, only: num2str
  use sloshdyn_tables, only: table_header
  implicit none
  private
  public :: design_report_t, report_lines, report_text, VERDICT_OK, VERDICT_NOT_OK, VERDICT_INFO, &
            verdict_names, REPORT_LINE_LEN, REPORT_TEXT_LEN, sub, pick

  !> Verdicts of a check.
  integer, parameter :: VERDICT_OK = 1, VERDICT_NOT_OK = 2, VERDICT_INFO = 3
  character(len=*), parameter :: verdict_names(3) = [character(len=6) :: 'OK', 'NOT OK', 'INFO']
  !> A required value equal to its capacity within round-off counts as OK (e.g. a freeboard of
  !> exactly the required one, or a record scaled so that the wave equals it).
  real(wp), parameter :: equal_within = 1.0e-9_wp
  !> The longest line of either table and the longest table as one text (the bridge's buffer).
  integer, parameter :: REPORT_LINE_LEN = 1600, REPORT_TEXT_LEN = 524288
  !> Digits of the substituted numbers (engineering precision).
  integer, parameter :: shown_digits = 5

  type :: check_row_t
    character(len=24) :: code = ''
    character(len=96) :: check = ''
    character(len=96) :: clause = ''
    real(wp) :: demand = 0, capacity = 0
    character(len=16) :: unit = ''
    integer :: verdict = VERDICT_INFO
  end type check_row_t

  type :: calc_row_t
    character(len=24) :: code = ''
    character(len=160) :: quantity = ''
    character(len=32) :: symbol = ''
    character(len=400) :: formula = ''
    character(len=600) :: substituted = ''
    real(wp) :: value = 0
    character(len=16) :: unit = ''
    character(len=96) :: clause = ''
  end type calc_row_t

  !> The rows recorded so far (n_checks, n_calc of the arrays' rows are used), and the code
  !> whose steps add and put record (a code module sets it when it starts).
  type :: design_report_t
    type(check_row_t), allocatable :: checks(:)
    type(calc_row_t), allocatable :: calc(:)
    integer :: n_checks = 0, n_calc = 0
    character(len=24) :: code = ''
  contains
    procedure :: step
    procedure :: add
    procedure :: put
    procedure :: note
    procedure :: check
    procedure :: info
  end type design_report_t

contains

  !> A step of the hand calculation: quantity (words), symbol, formula (symbolic), the
  !> substituted numbers (template with '@' where each of numbers goes, see sub), its value,
  !> unit and clause; returns the value, so that a formula is typed where it is recorded.
  function step(self, code, quantity, symbol, formula, template, numbers, value, unit, clause) &
    result(x)
    class(design_report_t), intent(inout) :: self
    character(len=*), intent(in) :: code, quantity, symbol, formula, template, unit, clause
    real(wp), intent(in) :: numbers(:), value
    real(wp) :: x
    type(calc_row_t), allocatable :: grown(:)
    if (.not. allocated(self%calc)) allocate (self%calc(64))
    if (self%n_calc == size(self%calc)) then
      allocate (grown(2*size(self%calc)))
      grown(1:self%n_calc) = self%calc
      call move_alloc(grown, self%calc)
    end if
    self%n_calc = self%n_calc + 1
    self%calc(self%n_calc) = calc_row_t(code, quantity, symbol, formula, sub(template, numbers), &
                                        value, unit, clause)
    x = value
  end function step

  !> A step of the current code (self%code); returns its value.
  function add(self, quantity, symbol, formula, template, numbers, value, unit, clause) result(x)
    class(design_report_t), intent(inout) :: self
    character(len=*), intent(in) :: quantity, symbol, formula, template, unit, clause
    real(wp), intent(in) :: numbers(:), value
    real(wp) :: x
    x = self%step(trim(self%code), quantity, symbol, formula, template, numbers, value, unit, &
                  clause)
  end function add

  !> A step of the current code whose value the caller has already.
  subroutine put(self, quantity, symbol, formula, template, numbers, value, unit, clause)
    class(design_report_t), intent(inout) :: self
    character(len=*), intent(in) :: quantity, symbol, formula, template, unit, clause
    real(wp), intent(in) :: numbers(:), value
    real(wp) :: x
    x = self%add(quantity, symbol, formula, template, numbers, value, unit, clause)
  end subroutine put

  !> A step that states a rule or an input in words (no formula): its value and unit.
  subroutine note(self, code, quantity, symbol, words, value, unit, clause)
    class(design_report_t), intent(inout) :: self
    character(len=*), intent(in) :: code, quantity, symbol, words, unit, clause
    real(wp), intent(in) :: value
    real(wp) :: unused
    unused = self%step(code, quantity, symbol, words, '@', [value], value, unit, clause)
  end subroutine note

  !> A check: demand against capacity (OK when demand <= capacity, within round-off).
  subroutine check(self, code, name, clause, demand, capacity, unit)
    class(design_report_t), intent(inout) :: self
    character(len=*), intent(in) :: code, name, clause, unit
    real(wp), intent(in) :: demand, capacity
    call add_check(self, check_row_t(code, name, clause, demand, capacity, unit, &
                                     merge(VERDICT_OK, VERDICT_NOT_OK, &
                                           demand <= capacity + equal_within*abs(capacity))))
  end subroutine check

  !> A value without a capacity (INFO): a load, a period.
  subroutine info(self, code, name, clause, value, unit)
    class(design_report_t), intent(inout) :: self
    character(len=*), intent(in) :: code, name, clause, unit
    real(wp), intent(in) :: value
    call add_check(self, check_row_t(code, name, clause, value, 0.0_wp, unit, VERDICT_INFO))
  end subroutine info

  subroutine add_check(self, row)
    type(design_report_t), intent(inout) :: self
    type(check_row_t), intent(in) :: row
    type(check_row_t), allocatable :: grown(:)
    if (.not. allocated(self%checks)) allocate (self%checks(16))
    if (self%n_checks == size(self%checks)) then
      allocate (grown(2*size(self%checks)))
      grown(1:self%n_checks) = self%checks
      call move_alloc(grown, self%checks)
    end if
    self%n_checks = self%n_checks + 1
    self%checks(self%n_checks) = row
  end subroutine add_check

  !> The template with its '@' replaced by the numbers in turn, each to 5 significant digits
  !> (a negative one in parentheses); a '@' without a number stays.
  pure function sub(template, numbers) result(text)
    character(len=*), intent(in) :: template
    real(wp), intent(in) :: numbers(:)
    character(len=600) :: text
    integer :: i, k, length
    text = ''
    length = 0
    k = 0
    do i = 1, len_trim(template)
      if (template(i:i) == '@' .and. k < size(numbers)) then
        k = k + 1
        call append(trim(shown(numbers(k))), text, length)
      else
        call append(template(i:i), text, length)
      end if
    end do
  contains
    pure subroutine append(piece, text, length)
      character(len=*), intent(in) :: piece
      character(len=*), intent(inout) :: text
      integer, intent(inout) :: length
      if (length + len(piece) > len(text)) return
      text(length + 1:length + len(piece)) = piece
      length = length + len(piece)
    end subroutine append
  end function sub

  !> yes where flag, else no (merge for texts of different lengths, e.g. with UTF-8
  !> symbols): trim the result.
  pure function pick(yes, no, flag) result(text)
    character(len=*), intent(in) :: yes, no
    logical, intent(in) :: flag
    character(len=max(len(yes), len(no))) :: text
    if (flag) then
      text = yes
    else
      text = no
    end if
  end function pick

  !> x to 5 significant digits, in parentheses when negative.
  pure function shown(x) result(text)
    real(wp), intent(in) :: x
    character(len=64) :: text
    if (x < 0) then
      text = '('//num2str(x, shown_digits)//')'
    else
      text = num2str(x, shown_digits)
    end if
  end function shown

  !> The lines (header first) of table 'design_checks' or 'design_calc' as CSV: text fields
  !> quoted where they hold a comma or a quote, numbers in full precision; an INFO check has
  !> no capacity and no ratio (empty fields).
  pure function report_lines(report, table) result(lines)
    type(design_report_t), intent(in) :: report
    character(len=*), intent(in) :: table
    character(len=REPORT_LINE_LEN), allocatable :: lines(:)
    integer :: i
    if (table == 'design_checks') then
      allocate (lines(report%n_checks + 1))
      do i = 1, report%n_checks
        associate (r => report%checks(i))
          lines(i + 1) = trim(csv(r%code))//','//trim(csv(r%check))//','// &
                         trim(csv(r%clause))//','//trim(number(r%demand))//','// &
                         trim(merge(number(r%capacity), repeat(' ', 32), &
                                    r%verdict /= VERDICT_INFO))//','//trim(csv(r%unit))//','// &
                         trim(merge(number(ratio(r)), repeat(' ', 32), &
                                    r%verdict /= VERDICT_INFO))//','// &
                         trim(verdict_names(r%verdict))
        end associate
      end do
    else
      allocate (lines(report%n_calc + 1))
      do i = 1, report%n_calc
        associate (r => report%calc(i))
          lines(i + 1) = trim(csv(r%code))//','//num2str(i)//','//trim(csv(r%quantity))//','// &
                         trim(csv(r%symbol))//','//trim(csv(r%formula))//','// &
                         trim(csv(r%substituted))//','//trim(number(r%value))//','// &
                         trim(csv(r%unit))//','//trim(csv(r%clause))
        end associate
      end do
    end if
    lines(1) = table_header(table)
  end function report_lines

  !> The table's lines joined by newlines (each line ends in one), '' past REPORT_TEXT_LEN
  !> with overflow = .true.
  pure subroutine report_text(report, table, text, overflow)
    type(design_report_t), intent(in) :: report
    character(len=*), intent(in) :: table
    character(len=REPORT_TEXT_LEN), intent(out) :: text
    logical, intent(out) :: overflow
    character(len=REPORT_LINE_LEN), allocatable :: lines(:)
    integer :: i, length, n
    lines = report_lines(report, table)
    text = ''
    length = 0
    overflow = .false.
    do i = 1, size(lines)
      n = len_trim(lines(i))
      if (length + n + 1 > len(text)) then
        overflow = .true.
        text = ''
        return
      end if
      text(length + 1:length + n + 1) = lines(i)(1:n)//new_line('a')
      length = length + n + 1
    end do
  end subroutine report_text

  pure real(wp) function ratio(row)
    type(check_row_t), intent(in) :: row
    if (row%capacity /= 0) then
      ratio = row%demand/row%capacity
    else
      ratio = merge(0.0_wp, huge(1.0_wp), row%demand <= 0)
    end if
  end function ratio

  !> A real in full precision, as every result table writes it.
  pure function number(x) result(text)
    real(wp), intent(in) :: x
    character(len=32) :: text
    write (text, '(es24.16e3)') x
    text = adjustl(text)
  end function number

  !> A text field of a CSV line: trimmed, in double quotes (its quotes doubled) when it holds a
  !> comma or a quote.
  pure function csv(field) result(text)
    character(len=*), intent(in) :: field
    character(len=2*len_trim(field) + 2) :: text
    integer :: i, length
    if (scan(trim(field), ',"') == 0) then
      text = trim(field)
      return
    end if
    text = '"'
    length = 1
    do i = 1, len_trim(field)
      if (field(i:i) == '"') then
        text(length + 1:length + 2) = '""'
        length = length + 2
      else
        text(length + 1:length + 1) = field(i:i)
        length = length + 1
      end if
    end do
    text(length + 1:length + 1) = '"'
  end function csv
end module sloshdyn_design_report
