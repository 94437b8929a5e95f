!> Time per UMAT call (benchmark, not a test): elastic, viscoplastic (both frames) and rate-independent
!> steps, 3D (NTENS 6) and plane strain (NTENS 4). Each case cycles through 64 slightly different
!> strain increments from one start state, so the local iteration counts vary as in a real mesh.
!> Prints one Markdown table row per case: median CPU ns per call over the repetitions (cpu_time:
!> the process's CPU time, which other jobs on a shared machine disturb less than wall time), the
!> spread, and the median local Newton iterations. Linked with the library or with the single-file UMAT
!> compiled as a host compiles it (bench/run_umat_bench.sh).
!> Usage: umat_bench [calls_per_repetition] [repetitions] [elastic|vp|ri]
!>        umat_bench <calls> 1 fuzz [results_file]: the distribution of single-call times over random
!>        (seeded, reproducible) materials, states, strain increments and time steps, the kind of input
!>        a fuzzer passes; optionally every call's STRESS, STATEV 1-32 and clock ticks (ns) written to
!>        results_file.
program umat_bench
  use, intrinsic :: iso_fortran_env, only: real64, int64, output_unit
  implicit none
  integer, parameter :: nstatv = 36, nvar = 64
  real(real64), parameter :: pi = 3.141592653589793_real64
  real(real64) :: woodford(23)
  integer :: ncalls, nrep
  character(len=32) :: arg, only

  woodford = [0.5_real64, 2900.0_real64, 18000.0_real64, 13000.0_real64, 4100.0_real64, 6900.0_real64, &
    1.46_real64, 0.00013_real64, 0.73_real64, -0.20_real64, 0.40_real64, 2.0_real64, 1.3e13_real64, &
    4600.0_real64, 3100.0_real64, 1.46_real64, 0.0026_real64, 35.0_real64, 1.3e10_real64, 0.0_real64, &
    0.0_real64, 0.0_real64, 1.0_real64]
  ncalls = 200000
  nrep = 7
  if (command_argument_count() >= 1) then
    call get_command_argument(1, arg); read (arg, *) ncalls
  end if
  if (command_argument_count() >= 2) then
    call get_command_argument(2, arg); read (arg, *) nrep
  end if
  only = ''
  if (command_argument_count() >= 3) call get_command_argument(3, only)   ! run only this kind

  if (trim(only) == 'fuzz') then
    call run_fuzz()
    stop
  end if
  write (output_unit, '(a)') '| case | NTENS | median ns/call | min-max ns/call | median local iterations |'
  write (output_unit, '(a)') '|---|---|---|---|---|'
  call run_case('elastic (both frames inside)', 6, 'elastic')
  call run_case('viscoplastic, both frames yield', 6, 'vp')
  call run_case('rate-independent (eta = 0), both frames', 6, 'ri')
  call run_case('elastic (both frames inside)', 4, 'elastic')
  call run_case('viscoplastic, both frames yield', 4, 'vp')
  call run_case('rate-independent (eta = 0), both frames', 4, 'ri')

contains

  subroutine run_case(name, ntens, kind)
    character(len=*), intent(in) :: name, kind
    integer, intent(in) :: ntens
    real(real64) :: props(23), stress0(ntens), statev0(nstatv), stress(ntens), statev(nstatv)
    real(real64) :: dstran(ntens, nvar), ddsdde(ntens, ntens), pnewdt, dtime, u(6), times(nrep), th, &
                    c0, c1
    real(real64), parameter :: base(6) = [-1.0_real64, -1.0_real64, -3.0_real64, 0.0_real64, 0.0_real64, 0.0_real64]
    real(real64) :: iters(nvar), sse, spd, scd, rpl, ddsddt(ntens), drplde(ntens), drpldt, stran(ntens), &
                    time(2), temp, dtemp, predef(1), dpred(1), coords(3), drot(3, 3), celent, f0(3, 3), f1(3, 3)
    integer :: i, k, r, jstep(4)
    character(len=80) :: cmname
    external :: umat

    if (len_trim(only) > 0 .and. trim(only) /= kind) return

    props = woodford
    th = 30 * pi / 180
    if (ntens == 4) then
      props(21:23) = [sin(th), cos(th), 0.0_real64]
    else
      props(21:23) = [sin(th), 0.0_real64, cos(th)]
    end if
    statev0 = 0
    statev0(1:6) = [-35.0_real64, -35.0_real64, -35.0_real64, 0.0_real64, 0.0_real64, 0.0_real64]
    statev0(14:19) = statev0(1:6)
    stress0 = statev0(1:ntens)
    dtime = 10
    select case (kind)
    case ('elastic')
      statev0(13) = 60; statev0(26) = 60       ! both surfaces well outside -35 MPa
    case ('vp')
      statev0(13) = 2; statev0(26) = 35        ! the paper's start: hard far outside, soft on its surface
    case default
      props(13) = 0; props(19) = 0
      statev0(13) = 30; statev0(26) = 35
    end select
    call random_seed(put=[(1234 + i, i = 1, 64)])
    do k = 1, nvar
      call random_number(u)
      dstran(:, k) = 1.0e-5_real64 * (base(1:ntens) + (u(1:ntens) - 0.5_real64))
    end do
    if (kind == 'elastic') dstran = 0.1_real64 * dstran
    sse = 0; spd = 0; scd = 0; stran = 0; time = 0; temp = 0; dtemp = 0; predef = 0; dpred = 0; coords = 0
    drot = reshape([1, 0, 0, 0, 1, 0, 0, 0, 1], [3, 3]); celent = 1; f0 = 0; f1 = 0; jstep = 1
    cmname = 'CAMCLAY9'
    do k = 1, nvar
      stress = stress0; statev = statev0; pnewdt = 1
      call umat(stress, statev, ddsdde, sse, spd, scd, rpl, ddsddt, drplde, drpldt, stran, dstran(:, k), &
                time, dtime, temp, dtemp, predef, dpred, cmname, 3, ntens - 3, ntens, nstatv, props, 23, &
                coords, drot, pnewdt, celent, f0, f1, 1, 1, 1, 1, jstep, 1)
      iters(k) = statev(33)
    end do
    do r = 1, nrep
      call cpu_time(c0)
      do i = 1, ncalls
        k = 1 + mod(i, nvar)
        stress = stress0; statev = statev0
        call umat(stress, statev, ddsdde, sse, spd, scd, rpl, ddsddt, drplde, drpldt, stran, dstran(:, k), &
                  time, dtime, temp, dtemp, predef, dpred, cmname, 3, ntens - 3, ntens, nstatv, props, 23, &
                  coords, drot, pnewdt, celent, f0, f1, 1, 1, 1, 1, jstep, 1)
      end do
      call cpu_time(c1)
      times(r) = (c1 - c0) / ncalls * 1e9_real64
    end do
    write (output_unit, '(a,a,a,i0,a,f9.1,a,f9.1,a,f9.1,a,f5.1,a)') '| ', name, ' | ', ntens, ' | ', median(times), &
      ' | ', minval(times), ' - ', maxval(times), ' | ', median(iters), ' |'
  end subroutine run_case

  !> ncalls single calls in 8 blocks, one material per block (Woodford with viscosities, pc0 and
  !> lambda_p scaled by random powers of ten; block 8 rate independent), each call from a random
  !> initialised state (frame stresses around -p with a random deviator, pc of 0.1-300 MPa) with a
  !> random strain increment of 1e-7 to 1e-2 and DTIME of 1e-3 to 1e5 s. Prints median, p90, p99,
  !> p99.9 and max of the time per call, and how many calls used the fallback (STATEV(34) bit 16)
  !> and were rejected (PNEWDT < 1).
  subroutine run_fuzz()
    integer, parameter :: nblock = 8
    real(real64) :: props(23), stress(6), statev(nstatv), ddsdde(6, 6), dstran(6), pnewdt, dtime, u(40), &
                    p, sse, spd, scd, rpl, ddsddt(6), drplde(6), drpldt, stran(6), time(2), temp, dtemp, &
                    predef(1), dpred(1), coords(3), drot(3, 3), celent, f0(3, 3), f1(3, 3), t_sorted(ncalls)
    integer(int64) :: t0, t1, rate, ticks(ncalls)
    integer :: i, b, nfall, nrej, jstep(4), unit_out
    character(len=256) :: out_file
    character(len=80) :: cmname
    external :: umat
    out_file = ''
    if (command_argument_count() >= 4) call get_command_argument(4, out_file)
    if (len_trim(out_file) > 0) open (newunit=unit_out, file=trim(out_file), status='replace', action='write')
    sse = 0; spd = 0; scd = 0; stran = 0; time = 0; temp = 0; dtemp = 0; predef = 0; dpred = 0; coords = 0
    drot = reshape([1, 0, 0, 0, 1, 0, 0, 0, 1], [3, 3]); celent = 1; f0 = 0; f1 = 0; jstep = 1
    cmname = 'CAMCLAY9'
    call random_seed(put=[(4321 + i, i = 1, 64)])
    nfall = 0
    nrej = 0
    call system_clock(t0, rate)
    do i = 1, ncalls
      b = 1 + ((i - 1) * nblock) / ncalls
      if (i == 1 .or. b /= 1 + ((i - 2) * nblock) / ncalls) then
        call random_number(u)
        props = woodford
        props(21:23) = [u(1) - 0.5_real64, u(2) - 0.5_real64, u(3) + 0.1_real64]
        props(13) = props(13) * 10**(8 * u(4) - 6)
        props(19) = props(19) * 10**(8 * u(5) - 6)
        props(12) = props(12) * 10**(2 * u(6) - 1)
        props(18) = props(18) * 10**(2 * u(7) - 1)
        props(8) = props(8) * 10**(2 * u(8) - 1)
        props(17) = props(17) * 10**(2 * u(9) - 1)
        if (b == nblock) props([13, 19]) = 0
      end if
      call random_number(u)
      p = 10**(3 * u(1) - 0.5_real64)
      statev = 0
      statev(1:6) = -p * [1, 1, 1, 0, 0, 0] + p * (u(2:7) - 0.5_real64)
      statev(14:19) = -p * [1, 1, 1, 0, 0, 0] + p * (u(8:13) - 0.5_real64)
      statev(13) = 10**(3.5_real64 * u(14) - 1)
      statev(26) = 10**(3.5_real64 * u(15) - 1)
      stress = 0.5_real64 * (statev(1:6) + statev(14:19))
      dstran = 10**(5 * u(16) - 7) * (u(17:22) - [0.7_real64, 0.7_real64, 0.7_real64, 0.5_real64, &
                                                   0.5_real64, 0.5_real64])
      dtime = 10**(8 * u(23) - 3)
      pnewdt = 1
      call system_clock(t0)
      call umat(stress, statev, ddsdde, sse, spd, scd, rpl, ddsddt, drplde, drpldt, stran, dstran, &
                time, dtime, temp, dtemp, predef, dpred, cmname, 3, 3, 6, nstatv, props, 23, &
                coords, drot, pnewdt, celent, f0, f1, 1, 1, 1, 1, jstep, 1)
      call system_clock(t1)
      ticks(i) = t1 - t0
      if (pnewdt < 1) then
        nrej = nrej + 1
      else if (iand(nint(statev(34)), 16) /= 0) then
        nfall = nfall + 1
      end if
      if (len_trim(out_file) > 0) write (unit_out, '(i0,1x,l1,38es24.16,1x,i0)') i, pnewdt < 1, stress, &
                                          statev(1:32), ticks(i)
    end do
    if (len_trim(out_file) > 0) close (unit_out)
    t_sorted = real(ticks, real64) / rate * 1e9_real64
    call shell_sort(t_sorted)
    write (output_unit, '(a)') '| calls | median ns | p90 ns | p99 ns | p99.9 ns | max ns | fallback calls | rejected |'
    write (output_unit, '(a)') '|---|---|---|---|---|---|---|---|'
    write (output_unit, '(a,i0,5(a,f0.0),a,i0,a,i0,a)') '| ', ncalls, ' | ', t_sorted(pct(50.0_real64)), &
      ' | ', t_sorted(pct(90.0_real64)), ' | ', t_sorted(pct(99.0_real64)), ' | ', &
      t_sorted(pct(99.9_real64)), ' | ', t_sorted(ncalls), ' | ', nfall, ' | ', nrej, ' |'
  end subroutine run_fuzz

  integer function pct(q)
    real(real64), intent(in) :: q
    pct = max(1, min(ncalls, nint(q / 100 * ncalls)))
  end function pct

  subroutine shell_sort(x)
    real(real64), intent(inout) :: x(:)
    real(real64) :: t
    integer :: gap, i, j
    gap = size(x) / 2
    do while (gap > 0)
      do i = gap + 1, size(x)
        t = x(i)
        j = i
        do while (j > gap)
          if (x(j - gap) <= t) exit
          x(j) = x(j - gap)
          j = j - gap
        end do
        x(j) = t
      end do
      gap = merge(gap / 2, (gap * 5) / 11, gap == 2)
    end do
  end subroutine shell_sort

  function median(x) result(m)
    real(real64), intent(in) :: x(:)
    real(real64) :: m, y(size(x)), t
    integer :: i, j
    y = x
    do i = 2, size(y)
      t = y(i)
      j = i - 1
      do while (j >= 1)
        if (y(j) <= t) exit
        y(j + 1) = y(j)
        j = j - 1
      end do
      y(j + 1) = t
    end do
    m = 0.5_real64 * (y((size(y) + 1) / 2) + y(size(y) / 2 + 1))
  end function median

end program umat_bench
