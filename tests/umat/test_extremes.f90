!> Extremes (issue #2): dt = 0 and 1e-12 ... 1e12 s, eta from 0 to 1e30, strain increments up to 10 % in
!> any direction, tension, pc near zero, phi = 0 and 1, any bedding angle, NTENS 6 and 4. Every call
!> must return finite STRESS, STATEV and DDSDDE, and either a converged state or PNEWDT < 1 with STRESS
!> and STATEV exactly as they came in. A structured sweep, then >= 1e6 seeded random calls.
program test_extremes
  use, intrinsic :: iso_fortran_env, only: real64, int64, output_unit
  use test_support
  implicit none
  integer(int64) :: calls = 0, cutbacks = 0, bad = 0, fallbacks = 0, floors = 0, outruns = 0
  integer(int64) :: n_random
  logical :: verbose = .false.
  character(len=32) :: arg

  verbose = command_argument_count() >= 2
  call structured_sweep()
  write (output_unit, '(a,i0,a,i0,a,i0,a,i0,a,i0)') 'sweep: calls ', calls, ', cutbacks ', cutbacks, &
    ', failures ', bad, ', fallback solves ', fallbacks, ', steps that outrun the softening ', outruns
  call check_true('sweep: no failures', bad == 0)
  call check_true('sweep: cutbacks below 1 %', cutbacks * 100 < calls)

  n_random = 1000000
  if (command_argument_count() >= 1) then
    call get_command_argument(1, arg)
    read (arg, *) n_random
  end if
  verbose = command_argument_count() >= 2
  calls = 0; cutbacks = 0; bad = 0; fallbacks = 0; floors = 0; outruns = 0
  call random_calls(n_random)
  write (output_unit, '(a,i0,a,i0,a,i0,a,i0,a,i0,a,i0)') 'random: calls ', calls, ', cutbacks ', cutbacks, &
    ', failures ', bad, ', fallback solves ', fallbacks, ', pc at floor ', floors, ', steps that outrun the softening ', &
    outruns
  call check_true('random: no failures', bad == 0)
  call check_true('random: cutbacks below 0.1 %', cutbacks * 1000 < calls)
  call finish('test_extremes')

contains

  !> One call, checked. ok: converged (pnewdt >= 1) or cut back cleanly.
  subroutine checked_call(props, ntens, stress0, statev0, dstran, dtime)
    real(real64), intent(in) :: props(:), stress0(:), statev0(:), dstran(:), dtime
    integer, intent(in) :: ntens
    real(real64) :: stress(ntens), statev(nstatv_test), d(ntens, ntens), pnewdt
    logical :: finite
    stress = stress0(1:ntens); statev = statev0; pnewdt = 1
    call call_umat(props, ntens, stress, statev, 0 * dstran(1:ntens), dstran(1:ntens), dtime, d, pnewdt)
    calls = calls + 1
    finite = all(abs(stress) <= huge(1.0_real64)) .and. all(abs(statev) <= huge(1.0_real64)) .and. &
             all(abs(d) <= huge(1.0_real64)) .and. abs(pnewdt) <= huge(1.0_real64)
    if (.not. finite) then
      bad = bad + 1
      if (bad <= 5) write (output_unit, '(a,es10.2,a,8es11.3)') 'non-finite result: dtime ', dtime, &
        ' props/dstran ', props(13), props(19), dstran(1:min(6, ntens))
      return
    end if
    if (pnewdt < 1) then
      cutbacks = cutbacks + 1
      if (verbose .and. cutbacks <= 40) write (output_unit, '(a,i2,a,es9.2,a,2es9.2,a,f4.1,a,*(es10.2))') &
        'cutback ntens ', ntens, ' dt ', dtime, ' eta ', props(13), props(19), ' phi ', props(1), ' deps ', &
        dstran(1:min(6, ntens)), props(21:23), statev0(13), statev0(26), stress0
      if (any(stress /= stress0(1:ntens)) .or. any(statev /= statev0)) then
        bad = bad + 1
        if (bad <= 5) write (output_unit, '(a)') 'cutback changed STRESS or STATEV'
      end if
      return
    end if
    if (statev(13) <= 0 .or. statev(26) <= 0) then
      bad = bad + 1
      if (bad <= 5) write (output_unit, '(a)') 'non-positive pc after a converged call'
      return
    end if
    if (iand(nint(statev(34)), 16) /= 0) fallbacks = fallbacks + 1
    if (iand(nint(statev(34)), 32 + 64) /= 0) outruns = outruns + 1
    if (iand(nint(statev(34)), 3) /= 0) floors = floors + 1
  end subroutine checked_call

  subroutine structured_sweep()
    real(real64), parameter :: dts(7) = [0.0_real64, 1e-12_real64, 1e-6_real64, 1.0_real64, 1e3_real64, &
                                         1e6_real64, 1e12_real64]
    real(real64), parameter :: etas(5) = [0.0_real64, 1.0_real64, 1e10_real64, 1e13_real64, 1e30_real64]
    real(real64), parameter :: mags(3) = [1e-6_real64, 1e-3_real64, 0.1_real64]
    real(real64), parameter :: phis(3) = [0.0_real64, 0.5_real64, 1.0_real64]
    real(real64), parameter :: thetas(4) = [0.0_real64, 45.0_real64, 90.0_real64, 67.0_real64]
    real(real64) :: props(23), dirs(6, 7), stress0(6), statev0(nstatv_test), th, n(3)
    integer :: idt, ieta, imag, idir, iphi, ith, istate, ntens
    dirs(:, 1) = [-1, -1, -1, 0, 0, 0]         ! isotropic compression
    dirs(:, 2) = [1, 1, 1, 0, 0, 0]            ! isotropic extension (tension)
    dirs(:, 3) = [0, 0, -1, 0, 0, 0]           ! uniaxial compression
    dirs(:, 4) = [0, 1, 0, 0, 0, 0]            ! uniaxial extension
    dirs(:, 5) = [0, 0, 0, 2, 0, 0]            ! simple shear
    dirs(:, 6) = [1, -1, 0, 0, 1, 0]           ! isochoric mixed
    dirs(:, 7) = [-0.3_real64, 0.2_real64, -1.0_real64, 0.5_real64, -0.4_real64, 0.7_real64]
    do ith = 1, 4
      th = thetas(ith) * pi / 180
      do iphi = 1, 3
        do ieta = 1, 5
          do istate = 1, 5
            do ntens = 4, 6, 2
              if (ntens == 4) then
                n = [sin(th), cos(th), 0.0_real64]
              else
                n = [sin(th), 0.0_real64, cos(th)]
              end if
              props = props_with(phis(iphi), n, etas(ieta), etas(ieta))
              call initial_state(istate, stress0, statev0)
              do idt = 1, size(dts)
                do imag = 1, 3
                  do idir = 1, 7
                    call checked_call(props, ntens, stress0, statev0, dirs(:, idir) / norm2(dirs(:, idir)) &
                                      * mags(imag), dts(idt))
                  end do
                end do
              end do
            end do
          end do
        end do
      end do
    end do
  end subroutine structured_sweep

  !> 1: uninitialised at -35 MPa; 2: tension +5 MPa with pc = 30; 3: pc near zero (1e-5 MPa);
  !> 4: deviatoric, far outside the hard surface; 5: a soft-frame state under the indenter in
  !> loading_rate_a1's hold where the fallback solver fires and the step outruns the softening
  !> (test_support's hold_stress: pc_soft 995 MPa, p' 446 MPa).
  subroutine initial_state(which, stress0, statev0)
    integer, intent(in) :: which
    real(real64), intent(out) :: stress0(6), statev0(nstatv_test)
    statev0 = 0
    select case (which)
    case (1)
      stress0 = [-35, -35, -35, 0, 0, 0]
    case (2)
      stress0 = [5, 5, 5, 0, 0, 0]
      statev0(13) = 30; statev0(26) = 30
    case (3)
      stress0 = [-1.0_real64, -2.0_real64, -1.5_real64, 0.3_real64, 0.0_real64, 0.0_real64]
      statev0(13) = 1e-5_real64; statev0(26) = 1e-5_real64
    case (5)
      stress0 = [hold_stress, 0.0_real64, 0.0_real64]
      statev0(13) = 2; statev0(26) = hold_pc_soft
    case default
      stress0 = [-10, -10, -90, 5, 0, 0]
      statev0(13) = 2; statev0(26) = 35
    end select
    if (which > 1) then
      statev0(1:6) = stress0
      statev0(14:19) = stress0
    end if
  end subroutine initial_state

  !> Seeded random calls over the whole admissible range.
  subroutine random_calls(ncalls)
    integer(int64), intent(in) :: ncalls
    real(real64) :: props(23), stress0(6), statev0(nstatv_test), dstran(6), dtime, u(24), n(3), phi, p, mag
    integer :: seed(64), nseed, ntens
    integer(int64) :: k
    call random_seed(size=nseed)
    seed = 20201112
    call random_seed(put=seed(1:nseed))
    do k = 1, ncalls
      call random_number(u)
      ntens = merge(4, 6, u(1) < 0.3_real64)
      n = 2 * u(2:4) - 1
      if (ntens == 4) n(3) = 0
      if (norm2(n) < 1e-3_real64) n = [0.0_real64, 1.0_real64, 0.0_real64]
      phi = merge(0.0_real64, merge(1.0_real64, u(5), u(5) > 0.8_real64), u(5) < 0.2_real64)
      props = props_with(phi, n, eta_of(u(6)), eta_of(u(7)))
      ! dt: 0 sometimes, else 1e-12 ... 1e12 s.
      dtime = merge(0.0_real64, 10**(-12 + 24 * u(8)), u(8) < 0.02_real64)
      ! Strain increment: random direction, magnitude 1e-8 ... 0.1.
      dstran = 2 * u(9:14) - 1
      mag = 10**(-8 + 7 * u(15))
      dstran = dstran / norm2(dstran) * mag
      if (ntens == 4) dstran(5:6) = 0
      ! Frame stresses: mean pressure -20 ... 300 MPa (tension included), deviator up to 2 p + 20.
      statev0 = 0
      p = -20 + 320 * u(16)**2
      stress0 = -p * [1, 1, 1, 0, 0, 0] + (abs(p) + 20) * (2 * u([17, 18, 19, 20, 21, 22]) - 1)
      if (ntens == 4) stress0(5:6) = 0
      statev0(1:6) = stress0
      statev0(14:19) = stress0 * (0.5_real64 + u(23))
      if (ntens == 4) statev0(18:19) = 0
      ! pc: 1e-6 ... 1e3 MPa.
      statev0(13) = 10**(-6 + 9 * u(24))
      statev0(26) = 10**(-6 + 9 * u(16))
      stress0 = phi * statev0(1:6) + (1 - phi) * statev0(14:19)
      call checked_call(props, ntens, stress0, statev0, dstran, dtime)
    end do
  end subroutine random_calls

  !> 0 in one case out of five, else 1 ... 1e30.
  pure real(real64) function eta_of(v)
    real(real64), intent(in) :: v
    eta_of = merge(0.0_real64, 10**(30 * (v - 0.2_real64) / 0.8_real64), v < 0.2_real64)
  end function eta_of

end program test_extremes
